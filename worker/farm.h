/* farm: render one image with N forked processes sharing an anonymous mapping. */
#ifndef FARM_H
#define FARM_H

#include <signal.h>

#include "render.h"

#define FARM_MAX_PROCESSES 256

struct farm_proc {
    struct render_stats st;
    double wall_s, cpu_s;
    int done; /* the child wrote its stats */
};

struct farm_result {
    struct render_stats total;
    struct farm_proc proc[FARM_MAX_PROCESSES];
    int processes;
    double wall_s, cpu_s;
    int child_signal;  /* on failure: the signal that killed a render process, else 0 */
    int child_crashed; /* on failure: a render process died (signal or exit code), not a stop */
    int stopped;       /* on failure: *stop was set, the children were stopped */
    long peak_rss_kb;  /* largest resident set of any render child so far (getrusage) */
};

/* What the caller sees while a render runs: rows done of rows, seconds elapsed. */
typedef void (*farm_progress_fn)(void *arg, int rows_done, int rows, double elapsed_s);

struct farm_job {
    const struct scene *scene;
    const struct camera *camera;
    struct render_settings rs;
    struct sampler *pixel, *light;
    int processes;
    int row_part, row_parts; /* render only rows with row % row_parts == row_part (1 part: all) */
    farm_progress_fn progress;
    void *progress_arg;
    const volatile sig_atomic_t *stop; /* optional: when it becomes non-zero the render is abandoned */
};

/* A zeroed framebuffer of w*h*3 floats that forked children can write (a shared mapping).
   NULL + e on failure. Free with farm_framebuffer_free. */
float *farm_framebuffer_new(int w, int h, struct err *e);
void farm_framebuffer_free(float *rgb, int w, int h);

/* Render fj into rgb (from farm_framebuffer_new) (width*height*3 floats, linear). Rows are split over the
   processes as row % processes; every pixel depends only on (seed, x, y), so any split gives the same bytes.
   0 on success; -1 with e filled when a child fails (exit code or signal: the others are
   killed and reaped; res->child_crashed, res->child_signal say so), when *fj->stop becomes set
   (children killed and reaped; res->stopped), or when a resource is missing. A child whose
   parent dies is killed with it on Linux (PR_SET_PDEATHSIG), elsewhere stops after its current row. */
int farm_render(const struct farm_job *fj, float *rgb, struct farm_result *res, struct err *e);

#endif
