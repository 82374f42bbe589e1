/* queue_study: a compare job or suite in a queue spread over its workers (docs/farm.md): the worker
   that claims it writes one render entry per reference and per image into DIR/spread/<stem>/, a
   queue of its own that workers drain (queue_drain.h), and files the job there (job/<X>.yaml). This
   module makes the study's folder. */
#ifndef QUEUE_STUDY_H
#define QUEUE_STUDY_H

#include "job/jobfile.h"
#include "queue_claim.h"

/* Spread the claimed compare job DIR/running/name, read and parsed once into jf (its paths as at
   jf->path, stem its file's stem), over the queue; an invalid one goes to failed/ as any job. */
void queue_study_expand(struct queue *q, const char *name, const struct jobfile *jf, const char *stem);

/* 1 when a compare job or suite claimed into DIR/running/ by a live worker (lease_stale says not
   dead) is being spread: its name into name, its lease into holder (zeroed when not written yet).
   Its renders appear in DIR/spread/ once it is, or the claim goes to failed/, or its claimer dies
   and the claim is recovered: a --once worker with nothing else to do waits for that. */
int queue_study_spreading(const struct queue *q, struct lease *holder, char *name, size_t n);

/* Remove the folder tree at path (never following a link). */
void queue_study_remove_tree(const char *path);

/* Write the entry file dir/entry (a comment saying what it renders) atomically. 0 or -1 with e. */
int queue_study_write_entry(const char *dir, const char *entry, const char *what, struct err *e);

#endif
