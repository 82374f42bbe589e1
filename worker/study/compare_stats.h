/* compare_stats: a compare job's results across seeds: means and spread per sweep point,
   stability and structured error per variant, and the chart built from them. */
#ifndef COMPARE_STATS_H
#define COMPARE_STATS_H

#include "compare.h"

/* One (scene, variant, sweep point) over its seeds. rel* are relMSE; 0 when not measured. */
struct compare_agg {
    int n;                      /* seeds with a result */
    double spp, wall_s, cpu_s;  /* means */
    double rel, rel_lo, rel_hi; /* mean, min, max */
};

void compare_stats_aggregate(const struct compare *c, int scene, int variant, int point,
                             struct compare_agg *a);

/* Whether variant's sweep points in scene change its samples per pixel by more than 5% (not for
   a light_threshold, max_depth or poisson_pool sweep). */
int compare_stats_samples_vary(const struct compare *c, int scene, int variant);

/* The sweep points of (scene, variant) ordered by mean samples per pixel, fewest first, or in
   the sweep's own order when the sweep leaves samples per pixel alone (within 5%: a
   light_threshold sweep). order has c->n_points entries. */
void compare_stats_point_order(const struct compare *c, int scene, int variant, int *order);

/* relMSE of the mean of a point's seed images against ref, and the mean relMSE of the single
   images: noise falls by the seed count when averaged, structured error (the same in every
   seed) does not. Reads the images from dir: their float copies (<stem>.exr) when the scene's
   reference is linear, else the PNGs' display values. 0, or -1 with e filled. */
int compare_stats_seed_average(const struct compare *c, int scene, int variant, int point, const char *dir,
                               const struct rgbf *ref, double *rel_of_mean, double *mean_rel, struct err *e);

/* The share of (scene, variant, point)'s error that repeats in every seed, in [0, 1], from
   compare_stats_seed_average: 0 for pure noise, 1 for error every seed makes alike. *gain
   (optional): the mean relMSE over the relMSE of the mean. NAN when it cannot be told (one seed,
   an image unreadable). */
double compare_stats_repeat_share(const struct compare *c, int scene, int variant, int point, const char *dir,
                                  const struct rgbf *ref, double *gain);

/* One line for people on (scene, variant): spread across seeds, the slope of error against
   samples, where error stops falling as the threshold drops, and structured error at each
   point (ref may be NULL: then only what needs no reference). Its length grows with the sweep:
   a malloc'd string (caller frees), NULL when out of memory. */
char *compare_stats_stability(const struct compare *c, int scene, int variant, const char *dir,
                              const struct rgbf *ref);

/* chart.svg: per scene, relMSE against CPU time and against samples per pixel. */
char *compare_stats_chart_svg(const struct compare *c);

#endif
