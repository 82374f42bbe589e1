/* run: render one loaded job end to end (scene, samplers, farm, image, sidecar). */
#ifndef RUN_H
#define RUN_H

#include "farm.h"
#include "job.h"

struct run_opts {
    const char *out_dir;  /* default "out" */
    int processes;        /* > 0 overrides the job's */
    int quiet;
    int progress;         /* draw progress on stderr (a terminal, not quiet) */
};

struct run_result {
    char image_path[2048];
    char sidecar_path[2048];
    int width, height;
    struct farm_result farm;
};

/* Render j. Returns 0 on success, 2 when the job's input is bad (scene, reference: nothing
   rendered), 1 when rendering or writing failed; e says why. No output file exists unless the
   render completed: image and sidecar are written atomically. */
int run_job(const struct job *j, const struct run_opts *o, struct run_result *rr, struct err *e);

/* mkdir -p for path. 0 or -1 with e filled. */
int run_mkdirs(const char *path, struct err *e);

#endif
