/* procs: render one image with N forked processes sharing an anonymous mapping. */
#ifndef PROCS_H
#define PROCS_H

#include <signal.h>

#include "render/render.h"

#define PROCS_MAX_PROCESSES 256

struct procs_proc {
    struct render_stats st;
    double wall_s, cpu_s;
    int done; /* the child wrote its stats */
};

struct procs_result {
    struct render_stats total;
    struct procs_proc proc[PROCS_MAX_PROCESSES];
    int processes;
    double wall_s, cpu_s;
    int child_signal;  /* on failure: the signal that killed a render process, else 0 */
    int child_crashed; /* on failure: a render process died (signal or exit code), not a stop */
    int stopped;       /* on failure: *stop was set, the children were stopped */
    long peak_rss_kb;  /* largest resident set of any render child so far (getrusage) */
};

/* What the caller sees while a render runs: rows done of rows, seconds elapsed. */
typedef void (*procs_progress_fn)(void *arg, int rows_done, int rows, double elapsed_s);

struct procs_job {
    const struct scene *scene;
    const struct camera *camera;
    struct render_settings rs;
    struct sampler *pixel, *light;
    int processes;
    int row_part, row_parts; /* render only rows with row % row_parts == row_part (1 part: all) */
    procs_progress_fn progress;
    void *progress_arg;
    const volatile sig_atomic_t *stop; /* optional: when it becomes non-zero the render is abandoned */
};

/* A zeroed framebuffer of w*h*3 floats that forked children can write (a shared mapping).
   NULL + e on failure. Free with procs_framebuffer_free. */
float *procs_framebuffer_new(int w, int h, struct err *e);
void procs_framebuffer_free(float *rgb, int w, int h);

/* Render fj into rgb (from procs_framebuffer_new, linear), rows split over the processes as row %
   processes (a pixel depends only on (seed, x, y): any split gives the same bytes). 0; -1 with e
   filled when a child fails (the others killed and reaped; res->child_crashed, res->child_signal),
   when *fj->stop becomes set (res->stopped), or when a resource is missing. A child whose parent
   dies is killed with it on Linux, elsewhere stops after its current row. */
int procs_render(const struct procs_job *fj, float *rgb, struct procs_result *res, struct err *e);

/* Render fj's rows in the calling process, no fork (the study's cost design times small units of
   work, for which a fork costs more than the unit): res as procs_render's with one process, cpu_s
   this thread's. 0, or -1 with e filled (the render context could not be made). */
int procs_render_here(const struct procs_job *fj, float *rgb, struct procs_result *res, struct err *e);

/* The share of the render processes' CPU time spent drawing point sets, in [0, 1] (each process's
   sampler_s is a part of its cpu_s, and r sums both over the processes or parts merged). */
double procs_sampling_share(const struct procs_result *r);

#endif
