/* compare_stats: a compare job's results across seeds: means and spread per sweep point, and a
   point's seed images taken together. Statistics only: the rules that judge them are the
   verdict's (verdict.h), the words and pictures the report's. */
#ifndef COMPARE_STATS_H
#define COMPARE_STATS_H

#include "study/load/compare_model.h"

/* One (scene, variant, sweep point) over its seeds: means; rel is relMSE's, 0 when not measured. */
struct compare_agg {
    int n; /* seeds with a result */
    double spp, cpu_s, rel;
};

void compare_stats_aggregate(const struct compare *c, int scene, int variant, int point,
                             struct compare_agg *a);

/* The sweep points of (scene, variant) ordered by mean samples per pixel, fewest first, or in
   the sweep's own order when the sweep leaves samples per pixel alone (within 5%: a
   light_threshold sweep). order has c->n_points entries. */
void compare_stats_point_order(const struct compare *c, int scene, int variant, int *order);

/* What a point's seed images say together. */
struct compare_seed_stats {
    double rel_of_mean;        /* relMSE of the mean of the seeds' images against the reference */
    double bias_rel;           /* the relMSE of the reference scaled to that mean image's mean radiance: the
                                  part of rel_of_mean an offset in mean radiance alone makes */
    double *radiance;          /* the caller's array of c->n_seeds: each seed image's mean radiance */
    double *spec_ring;         /* the caller's array of c->n_seeds x VERDICT_SPEC_RINGS, or NULL: each seed
                                  image's error spectrum, log10 of each ring's power over its mean power */
    double peak_p, anisotropy; /* the seeds' pooled error spectrum's (errspec_look_of); NAN unknown */
};

/* The seed images of (scene, variant, point) against ref, over the scene's mask's pixels, read from dir:
   their float copies
   (<stem>.exr) when the scene's reference is linear, else the PNGs' display values. Averaging them
   divides noise by the seed count and leaves structured error; the verdict tells the two apart.
   0, or -1 with e filled. */
int compare_stats_seed_images(const struct compare *c, int scene, int variant, int point, const char *dir,
                              const struct rgbf *ref, struct compare_seed_stats *out, struct err *e);

/* The mean over an image's pixels (the mask's only; every pixel when mask is NULL) and channels. */
double compare_stats_mean_radiance(const struct rgbf *img, const struct img_mask *mask);

#endif
