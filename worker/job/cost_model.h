/* cost_model: what a render costs in CPU seconds, measured on this machine, for `--dry-run` and any
   caller that plans renders:

     cpu = samples x trace + pixels x pixel set + light sets x light set + padded sets x padded set

   A traced sample's cost comes from a short pilot of pixels, its point-set draws timed apart and
   taken out (a pilot's draws are not the render's); each set's cost from a few sets drawn alone
   (cost_sets.h), times the sets the render draws. Pilots and set timings are shared between
   estimates of equal settings, all within one budget of CPU seconds. */
#ifndef COST_MODEL_H
#define COST_MODEL_H

#include "job.h"
#include "scenefile/scene_load.h"

/* The pilot draws sets of at most this many points (a larger set's kind at a coarser threshold):
   small, so that a pilot's time is mostly tracing, the error of taking its draws out charged to
   every sample (one path beside a 4096-point pmj02bn set was 90 us). */
#define COST_PILOT_SET_MAX 64
/* Most pixels one pilot renders. */
#define COST_PILOT_PIXELS 64

struct cost_estimate {
    double spp_mean, samples; /* camera samples per pixel (a set's mean points) and in all */
    double cpu_s;             /* the render's CPU seconds, all processes */
    double trace_s, pixel_sets_s, light_sets_s, padded_sets_s; /* cpu_s's parts */
    double ns_per_sample;                                      /* a traced sample, draws taken out */
    double light_sets, padded_sets;                            /* the sets the render would draw */
    int sets_scaled; /* a set too large to draw was timed at smaller sizes and scaled */
    /* the pilot's pixels, their camera samples and those traced */
    int pilot_pixels;
    double pilot_samples, pilot_traced;
};

struct cost_model;

/* A model that spends about budget_s CPU seconds measuring (each pilot an equal share of what is
   left among those expected, each set timing a few sets; past it, a set is scaled from a timed one
   of its kind). NULL on no memory. Free with cost_model_free (accepts NULL). */
struct cost_model *cost_model_new(double budget_s);
void cost_model_free(struct cost_model *m);

/* Say, measuring nothing, that j's render at width x height of sf will be estimated, so that the
   budget is shared among the distinct pilots. 0, or -1 with e filled (no memory). */
int cost_model_expect(struct cost_model *m, const struct job *j, const struct scene_file *sf, int width,
                      int height, struct err *e);

/* Estimate j's render at width x height of the loaded scene sf, whatever its processes (their CPU
   time adds up). 0, or -1 with e filled (a sampler or scene the render would refuse, no memory). */
int cost_model_estimate(struct cost_model *m, const struct job *j, const struct scene_file *sf, int width,
                        int height, struct cost_estimate *out, struct err *e);

#endif
