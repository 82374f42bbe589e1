/* verdict_time: the figures per (variant, point) and the ranking at equal CPU time, which carries
   both uncertainties: the error's (paired by seed) and the cost's (the cost design's blocks,
   paired by block), combined by the delta method with Welch-Satterthwaite degrees of freedom and
   Holm-corrected over the ranking's pairs (docs/compare.md, "Equal CPU time"). */
#ifndef VERDICT_TIME_H
#define VERDICT_TIME_H

#include "verdict_figures.h"

/* A variant's own cheapest point may lie at most this factor above the common time when it has one
   point (no line to read along: its relMSE x time is compared, plain Monte Carlo's slope -1). */
#define VERDICT_TIME_ONE_POINT 1.25

/* Fill out's per (variant, point) figures (point_rel*, cost: allocated here) from f. 0 or -1 (out
   of memory). */
int verdict_time_points(const struct verdict_figures *f, struct verdict_scene *out);

/* Rank f's variants at equal CPU time into r (r->e allocated for f->n_variants; r->pair_p allocated
   here): the common time is the most every variant's points reach in the cost design's figures
   (out->cost, from verdict_time_points); each variant's relMSE there is read per seed along its
   error-against-time line in log-log (between its points, or beyond its cheapest along its first
   segment, `extrapolated`, at most as far as its points span; farther, or with one point farther
   than VERDICT_TIME_ONE_POINT: `untold`, separated from none). Never behind for costing more. 0
   or -1 (out of memory). */
int verdict_time_rank(const struct verdict_figures *f, const struct verdict_scene *out,
                      struct verdict_ranking *r);

#endif
