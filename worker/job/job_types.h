/* job_types: struct job, the one type every part of a job (job_path, outdir) shares, in a header
   of its own so that they include this and never job.h, whose source calls them. */
#ifndef JOB_TYPES_H
#define JOB_TYPES_H

#include <stdint.h>

#include "base/err.h"
#include "image/image.h"
#include "render/render_spec.h"
#include "scenefile/yamlx.h"

#define JOB_PATH_MAX 1024
#define JOB_NAME_MAX 128
#define JOB_OUTPUTS_MAX 4 /* images one job writes: one per format */

/* Most keys a job file may hold: its own and a render's (job_key_list; a test checks they fit). */
#define JOB_KEYS_MAX 32

/* Where each key was given (1-based line and column; 0 when absent), by job_key_list's index: for
   messages, and to tell a key given from its default (job_at, job_mark). */
struct job_pos {
    int at[JOB_KEYS_MAX][2];
};

struct job {
    char path[JOB_PATH_MAX]; /* the job file */
    char name[JOB_NAME_MAX];
    char scene_path[JOB_PATH_MAX]; /* resolved */
    struct render_spec spec;       /* everything that changes the pixels */
    int processes;
    enum img_format format;
    char output[JOB_NAME_MAX]; /* the image's file name (a list's first): its stem names the sidecar */
    int n_more;                /* output: [a.png, a.exr]: the images written beside it, one per format */
    char more_output[JOB_OUTPUTS_MAX - 1][JOB_NAME_MAX];
    enum img_format more_format[JOB_OUTPUTS_MAX - 1];
    char reference[JOB_PATH_MAX]; /* resolved; "" when none */
    int priority;                 /* queue order: higher first (default 0) */
    double entry_cpu_s;           /* a study spread over a queue: its entries' CPU target; 0: the queue's */
    int float_copy;               /* not a key: also write <stem>.exr beside a PNG or PPM (a compare's) */
    uint64_t hash;                /* FNV-1a of the job file's bytes, then its scene file's */
    struct job_pos pos;           /* parse positions, for messages only */
};

#endif
