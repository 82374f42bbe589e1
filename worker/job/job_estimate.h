/* job_estimate: what a job's render would cost, found without rendering it (`--dry-run`): its
   samples, memory and CPU time, from a short pilot of a few pixels rendered in this process. */
#ifndef JOB_ESTIMATE_H
#define JOB_ESTIMATE_H

#include <stddef.h>

#include "cost_model.h"
#include "job.h"
#include "scenefile/scene_load.h"

struct job_estimate {
    int width, height, processes;
    double spp_mean; /* camera samples per pixel, the pilot's mean (exact for the grid kinds) */
    double samples;  /* spp_mean x width x height */
    double cpu_s;    /* the whole render's CPU seconds (cost's) */
    double framebuffer_bytes, process_bytes; /* the shared image; one render process's resident set */
    double texture_bytes;      /* the scene's decoded image textures, loaded before the fork: shared */
    struct cost_estimate cost; /* the cost model's figures (cost_model.h) */
};

/* Estimate j's render with `processes` processes (0: the job's), writing nothing: the scene (sf,
   else j->scene_path's), size and limits checked as run_job checks them, then its cost by m. 0,
   or -1 with e filled (bad input, at the key's line:col as a render would say). */
int job_estimate(const struct job *j, const struct scene_file *sf, int processes, struct cost_model *m,
                 struct job_estimate *out, struct err *e);

/* Tell m that j will be estimated (cost_model_expect at the size job_estimate renders), so that
   its pilots share the budget. 0, or -1 with e filled. */
int job_estimate_expect(const struct job *j, const struct scene_file *sf, struct cost_model *m,
                        struct err *e);

/* The estimate's memory: the framebuffer, the textures (once) and every process's resident set. */
double job_estimate_memory(const struct job_estimate *est);

#endif
