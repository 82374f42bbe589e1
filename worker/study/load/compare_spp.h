/* compare_spp: a compare job's sweep given in samples per pixel (`sweep: { spp: [1, 4, 16] }`),
   mapped to each variant's camera threshold through the sampler's own set sizes. */
#ifndef COMPARE_SPP_H
#define COMPARE_SPP_H

#include "job/job.h"
#include "sample/sampler.h"
#include "scenefile/yamlx.h"

/* What sweep_keys says of an spp sweep (the report's "sweep: ..."), a format of the kind whose
   count is expected, not exact. */
#define COMPARE_SPP_SWEEP_NOTE                                                                               \
    "spp (each variant's threshold set so its sampler draws that many camera samples per pixel; "            \
    "%s: about)"

/* The threshold t at which a set of `kind` holds spp points: for the grid kinds, sobol and halton
   (n x n, n = floor(100 / t)) and pmj02bn and zsobol (n x n rounded up to a power of two), exactly,
   t = 100 / n for n = sqrt(spp) when spp is a square, else the smallest n that gives it; for poisson
   its expected count, t = sqrt(SAMPLER_POISSON_T2 / spp) to 4 digits. 0, or -1 when the kind
   gives no set of exactly spp points, with *below and *above the nearest counts it gives (0: none). */
int compare_spp_threshold(enum sampler_kind kind, long spp, double *t, long *below, long *above);

/* Apply a sweep's spp value v (a whole number in [1, SAMPLER_MAX_POINTS]) to j, whose sampler is
   set: j->threshold as compare_spp_threshold maps it, positioned at v. 0, or -1 with e at v: "spp:
   10: jitter sets hold n x n points (floor(100 / threshold) = n): 9 or 16, not 10". */
int compare_spp_apply(struct job *j, struct ydoc *d, yaml_node_t *v, struct err *e);

#endif
