/* sidecar: the JSON stats file written beside every image. */
#ifndef SIDECAR_H
#define SIDECAR_H

#include "farm.h"
#include "job.h"
#include "metrics.h"

struct sidecar {
    const struct job *job;
    int width, height;
    const struct farm_result *res;
    const struct metrics *error; /* NULL when the job has no reference */
    const char *image;           /* the image file's name */
};

/* Render the sidecar as JSON text into a malloc'd string (caller frees); NULL on no memory. */
char *sidecar_json(const struct sidecar *s);

#endif
