/* run_types: what a render of one job is given (run_opts) and what it gives back (run_result),
   shared by run.h and its part run_out.h, which includes this and never run.h. */
#ifndef RUN_TYPES_H
#define RUN_TYPES_H

#include <signal.h>

#include "image/metrics.h"
#include "job.h"
#include "outdir.h"
#include "procs.h"
#include "scenefile/scene_load.h"

struct run_opts {
    const char *out_dir; /* NULL: OUTDIR_DEFAULT (outdir.h) */
    int processes;       /* > 0 overrides the job's */
    int quiet;
    int progress;                      /* draw progress on stderr (a terminal, not quiet) */
    int force;                         /* render even when the outputs are current (resume off) */
    int part, parts;                   /* parts > 0: render rows with row % parts == part into a part file */
    const volatile sig_atomic_t *stop; /* optional: abandon the render when it becomes non-zero */
    void (*tick)(void *arg, int rows_done, int rows, double elapsed_s); /* optional: every ~5 ms */
    int (*may_write)(void *arg, const char *dir); /* optional: asked under the output folder's lock
                                          before writing: 0 = write nothing, fail (a queue claim
                                          taken over, the folder another queued job's) */
    void *tick_arg;                               /* the argument of tick, may_write and still_held */
    double lock_wait_s;            /* > 0: wait no longer for the output folder's lock (a queue: its
                                      lease timeout), then write without it if may_write says yes */
    int (*still_held)(void *arg);  /* optional: asked before each output is renamed into place: 0 =
                                      the claim was taken over; rename nothing more, fail */
    const struct scene_src *scene; /* optional: the job's scene as jobfile_open parsed it (NULL: read it) */
    const struct rgbf *ref;        /* optional: the job's reference, already read (NULL: read it) */
    enum img_domain ref_domain;    /* what ref holds (IMG_DISPLAY8: 8-bit display values) */
    const uint8_t *ref_bytes;      /* optional, without ref: j->reference's bytes (jobfile_open's) */
    size_t ref_len;
    const char *label;              /* optional: the progress line's name (NULL: the job's) */
    const struct rgb8 *ref_display; /* optional: the reference in 8 bits, a PNG/PPM image scored on it too */
};

struct run_result {
    struct outdir_files out; /* what the job writes (with parts: the part file), computed once */
    int width, height;
    int skipped;               /* outputs were current (same job hash): nothing rendered */
    int black;                 /* the image written is entirely black (run_print_warnings) */
    char scene_warning[600];   /* the scene's warning (scene_file.warning), run_print_warnings's */
    struct procs_result procs; /* on a render failure: child_crashed, child_signal, stopped */
    int has_error;             /* rendered against a reference: error holds the figures */
    struct metrics error;
    int has_display_error;        /* o->ref_display given and the image is PNG or PPM */
    struct metrics display_error; /* the 8-bit image against o->ref_display */
    enum img_domain error_domain; /* linear radiance, or 8-bit display values (a PNG/PPM reference) */
};

#endif
