/* job_estimate: what a job's render would cost, found without rendering it (`--dry-run`): its
   samples, memory and CPU time, from a short pilot of a few pixels rendered in this process. */
#ifndef JOB_ESTIMATE_H
#define JOB_ESTIMATE_H

#include <stddef.h>

#include "job.h"
#include "scenefile/scene_load.h"

/* Most pixels one pilot renders. */
#define JOB_ESTIMATE_PILOT_PIXELS 64

struct job_estimate {
    int width, height, processes;
    double spp_mean;      /* camera samples per pixel, the pilot's mean (exact for the grid kinds) */
    double samples;       /* spp_mean x width x height */
    double ns_per_sample; /* the pilot's CPU nanoseconds per camera sample */
    double cpu_s;         /* the whole render's CPU seconds, at the pilot's cost per pixel */
    double framebuffer_bytes, process_bytes; /* the shared image; one render process's resident set */
    double texture_bytes; /* the scene's decoded image textures, loaded before the fork: shared */
    int pilot_pixels;
    double pilot_samples, pilot_traced; /* the pilot pixels' camera samples, and how many it traced */
};

/* Estimate j's render with `processes` processes (0: the job's) and write nothing: the scene
   (sf, or loaded from j->scene_path when NULL), the size and the limits as run_job checks them,
   then a pilot of up to JOB_ESTIMATE_PILOT_PIXELS pixels spread over the image, rendered here
   until budget_s CPU seconds are spent (at least one path; a pixel too costly for the budget is
   cut short, its cost scaled from the paths traced). 0, or -1 with e filled (bad input,
   at the key's line:col as a render would say). */
int job_estimate(const struct job *j, const struct scene_file *sf, int processes, double budget_s,
                 struct job_estimate *out, struct err *e);

/* The estimate's memory: the framebuffer, the textures (once) and every process's resident set
   beside them. */
double job_estimate_memory(const struct job_estimate *est);

#endif
