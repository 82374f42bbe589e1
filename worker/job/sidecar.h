/* sidecar: the JSON stats file written beside every image. */
#ifndef SIDECAR_H
#define SIDECAR_H

#include "procs.h"
#include "job.h"
#include "image/metrics.h"

struct sidecar {
    const struct job *job;
    int width, height;
    const struct procs_result *res;
    const struct metrics *error;  /* NULL when the job has no reference */
    enum img_domain error_domain; /* what error was measured on: linear radiance or 8-bit values */
    const char *image;            /* the image file's name */
    int parts;                    /* > 0: merged from this many --part files (res->proc[i] = part i) */
};

/* The sidecar's record of the job's inputs: "job_hash": "<16 hex digits>". */
#define SIDECAR_HASH_KEY "\"job_hash\": \""

/* Render the sidecar as JSON text into a malloc'd string (caller frees); NULL on no memory. */
char *sidecar_json(const struct sidecar *s);

/* 1 when the sidecar at path exists and records job hash `hash`, else 0 (missing, unreadable,
   written for other inputs). */
int sidecar_matches(const char *path, uint64_t hash);

#endif
