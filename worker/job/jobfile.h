/* jobfile: a job file read and parsed once: its kind (a plain job, a compare job, a suite), the
   parsed document and its hash; for a plain job also its settings and its scene, read once. */
#ifndef JOBFILE_H
#define JOBFILE_H

#include <stddef.h>
#include <stdint.h>

#include "job.h"
#include "scenefile/scene_load.h"

enum jobfile_kind {
    JOBFILE_PLAIN,   /* one render */
    JOBFILE_COMPARE, /* variants: (a compare job, worker/study/) */
    JOBFILE_SUITE    /* studies: (compare jobs run as one) */
};

struct jobfile {
    char path[JOB_PATH_MAX]; /* where it belongs: messages and relative paths name it */
    enum jobfile_kind kind;
    struct ydoc doc; /* the file parsed (doc.file = path); a compare or suite loader reads it */
    uint8_t *bytes;  /* the file's bytes as read (a queue copies a compare job's) */
    size_t len;
    uint64_t hash;          /* FNV-1a of the file's bytes */
    struct job job;         /* JOBFILE_PLAIN: its settings, job.hash of all its inputs */
    struct scene_src scene; /* JOBFILE_PLAIN: its scene file, read and parsed once (run_opts.scene) */
    uint8_t *ref_bytes;     /* JOBFILE_PLAIN: its reference's bytes (run_opts.ref_bytes), or NULL */
    size_t ref_len;
};

/* Read the job file at `from` once (at most YDOC_MAX_BYTES), hash and parse it, as if it were at
   `path` (a queue's claim still belongs to the queue's folder); a plain job's keys checked, its
   scene and reference read and hashed. 0, or -1 with e naming path; jobfile_close after. */
int jobfile_open(struct jobfile *f, const char *from, const char *path, struct err *e);
void jobfile_close(struct jobfile *f);

/* The kind of the job file at `from`, read and parsed but not checked (a queue worker asks it of
   another worker's claim); JOBFILE_PLAIN also when it cannot be read or parsed. */
enum jobfile_kind jobfile_peek_kind(const char *from);

#endif
