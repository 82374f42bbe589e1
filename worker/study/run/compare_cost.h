/* compare_cost: what an image costs, measured on its own (docs/compare.md, "The cost design"):
   per scene, blocks that each time every (variant, point) once in a shuffled, seeded order, each
   timed unit about COMPARE_COST_UNIT_S of CPU (whole images repeated, or every k-th row of a large
   one), so that load drift hits every variant alike and the verdict can pair variants by block.
   The pixels of the timed renders are thrown away: the study's images are never touched. Also the
   order the study's images are rendered in (seed-major, shuffled), and cost.csv. */
#ifndef COMPARE_COST_H
#define COMPARE_COST_H

#include "job/run.h"
#include "study/load/compare_model.h"

/* Blocks per scene: the cost ratio of two variants is the mean of this many paired figures. */
#define COMPARE_COST_BLOCKS 10
/* CPU seconds one timed unit aims at: clock reads and a scheduler's time slice are small beside it. */
#define COMPARE_COST_UNIT_S 0.04
/* Most whole images one unit renders (a tiny image's unit is then shorter than the aim). */
#define COMPARE_COST_REPS_MAX 64

/* The order to render c's items in: seed-major (every scene, variant and point of seed 1, then of
   seed 2, ...), each seed's items shuffled by a generator seeded from the study's name: no variant
   renders in a stretch of machine load of its own. order gets c->n_items indices. */
void compare_cost_order(const struct compare *c, int *order);

/* Time every (scene, variant, point) of plan c (its items rendered or current: their samples and
   CPU seconds known in r, c's results) in COMPARE_COST_BLOCKS blocks into r->cost_s (allocated;
   r->n_blocks set). Renders with o's process count; nothing is written. 0, or -1 with e filled (a
   scene that does not load, out of memory, a render that failed). */
int compare_cost_measure(const struct compare *c, struct study_results *r, const struct run_opts *o,
                         struct err *e);

/* cost.csv's text (malloc'd; NULL on no memory): one row per (scene, variant, point, block):
   scene, variant, point (the first seed's image name without "-s<seed>.<ext>"), block, cpu_s (the
   CPU seconds one image of the point costs, timed in that block). */
char *compare_cost_csv(const struct compare *c);

/* Read dir/cost.csv into r, plan c's results (its items' images named as when written). 0, or -1
   when it is missing or does not cover every (scene, variant, point) of c: r->n_blocks stays 0 (the
   verdict falls back on the images' own CPU times and says so). */
int compare_cost_read(const struct compare *c, struct study_results *r, const char *dir);

#endif
