/* verdict_figures: one scene's figures (every variant, point and seed) and the thresholds the
   verdict judges them by: the types verdict.c and its parts (verdict_rank, verdict_say,
   verdict_look) share, so that the parts include this and never verdict.h (one direction). */
#ifndef VERDICT_FIGURES_H
#define VERDICT_FIGURES_H

#include <stdint.h>

#include "study/load/study_inputs.h"
#include "study/load/verdict_model.h"

/* A share of the error that repeats in every seed above this is structured (aliasing, a pattern,
   a bias): pure noise averages away across seeds. */
#define VERDICT_STRUCTURED_SHARE 0.5
/* A variant whose seeds' mean radiance is more standard errors than this off the reference's (the
   seeds' spread and the reference's noise together) is biased. */
#define VERDICT_BIAS_SE 4
/* The bias check needs this many seeds: with fewer, their spread is itself too uncertain (4
   standard errors from 2 seeds happen by chance 16% of the time, from 8 seeds 0.5%). */
#define VERDICT_BIAS_SEEDS 4
/* Heavy-tailed error (fireflies): at some point the seeds' relMSE span more than this factor (the
   largest over the smallest). An image's relMSE averages its pixels' squared errors, so with light
   tails (a finite fourth moment) its seeds agree within tens of percent; when rare, huge samples
   decide the error (an infinite variance, fireflies) the seeds that drew one stand far above those
   that did not, whether one seed drew them or half. Needs VERDICT_HEAVY_SEEDS seeds. */
#define VERDICT_HEAVY_RATIO 8
#define VERDICT_HEAVY_SEEDS 4
/* A point's relMSE within this factor of the reference's own is dominated by the reference's
   noise: warned. */
#define VERDICT_REF_NOISE 2
/* A sweep "changes the samples" when its points' mean samples per pixel span more than this ratio:
   a light_threshold, max_depth or poisson_pool sweep does not, though a poisson pixel sampler's
   counts move by a hair from point to point. */
#define VERDICT_SAMPLES_VARY 1.05
/* Error "stops falling" at a step whose local slope of log relMSE against log samples is above
   this (noise alone falls as spp^-1). */
#define VERDICT_STALL_SLOPE (-0.3)
/* A sampler's share of its render's CPU time above this is a failure: drawing the points costs
   more than tracing them. */
#define VERDICT_SAMPLER_SHARE 0.5
/* A reference with fewer than this many times the densest point's samples per pixel is too noisy
   to rank the densest points by, and its own noise is not taken out of any figure: its halves'
   difference misses the pixels where both halves agree by chance (both dark where the truth is
   not), so the estimate is low exactly where it matters (issue 38: 0.028 read against 0.048). */
#define VERDICT_REF_FACTOR 4

/* One scene of one study, every (variant, point, seed) at verdict_at(). Arrays are the caller's. */
struct verdict_figures {
    const char *study, *scene;
    int n_variants, n_points, n_seeds;
    const char *const *variants;  /* labels */
    const char *const *samplers;  /* per variant: its pixel sampler's name (sampler_kind.c) */
    const int *pools;             /* per variant: poisson_pool (0: fresh sets) */
    const char *const *points;    /* sweep point labels ("threshold 5") */
    const double *spp;            /* samples per pixel (mean over the image) */
    const double *cpu_s;          /* the render's CPU seconds */
    const double *relmse;         /* against the reference; NAN when not measured */
    const double *sampler_share;  /* fraction of CPU time drawing point sets */
    const uint64_t *nonfinite;    /* samples dropped as NaN or infinite */
    const double *rel_of_mean;    /* per (variant, point): relMSE of the seeds' mean image; NAN unknown */
    const double *bias_rel;       /* per (variant, point): the relMSE the mean image's offset in mean
                                     radiance alone gives (the reference scaled by it); NAN unknown */
    const double *radiance;       /* per (variant, point, seed): the image's mean radiance; NAN unknown */
    const double *lowfreq;        /* per (variant, point, seed): error_lowfreq (errspec.h); NAN unknown;
                                     NULL: none measured */
    const double *spec_ring;      /* per (variant, point, seed, ring): log10 of the ring's power over the
                                     image's mean power (errspec_look_of on one image); NULL: none */
    const double *spec_peak_p;    /* per (variant, point): the seeds' pooled spectrum's peak_p; NULL */
    const double *spec_aniso;     /* per (variant, point): its anisotropy; NULL: none */
    int n_blocks;                 /* the cost design's blocks */
    const double *cost_s;         /* per (variant, point, block): CPU seconds per image timed in the
                                     block (verdict_cost_at); NULL: none */
    int cost_from_images;         /* cost_s holds the images' own times, seed k as block k */
    enum verdict_rank_by rank_by; /* the centre over seeds of every relMSE figure (slopes: the mean) */
    struct study_ref_figures ref; /* the reference's samples per pixel (0 unknown), noise, radiance */
    int reference_unread;         /* the reference's pixels could not be read: no checks on images */
    int ref_noise_refused;        /* set by verdict_scene_compute: the reference is too sparse
                                     (VERDICT_REF_FACTOR) for its noise to be taken out */
    int images_unread;            /* (variant, point)s whose seed images could not be read */
};

static inline int verdict_at(const struct verdict_figures *f, int v, int p, int k)
{
    return (v * f->n_points + p) * f->n_seeds + k;
}

/* The mean over seeds of point p's figure x (one of f's arrays per (variant, point, seed)) for v. */
static inline double verdict_mean(const struct verdict_figures *f, const double *x, int v, int p)
{
    double s = 0;
    for (int k = 0; k < f->n_seeds; k++)
        s += x[verdict_at(f, v, p, k)];
    return s / f->n_seeds;
}

static inline int verdict_cost_at(const struct verdict_figures *f, int v, int p, int b)
{
    return (v * f->n_points + p) * f->n_blocks + b;
}

#endif
