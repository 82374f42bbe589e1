/* cost_sets: what one point set costs to draw (a pixel's, a light stream's, a padded one), measured
   on this machine for the cost model (cost_model.h) and cached: equal settings are timed once. */
#ifndef COST_SETS_H
#define COST_SETS_H

#include "base/err.h"
#include "sample/sampler.h"

/* Sets of a capacity above this are not drawn: timed at COST_SETS_SMALL and COST_SETS_DIRECT_MAX
   points and scaled as a power of the size. A kind that takes sets up to T points from a table
   (sampler_table_points) is timed at 2T and 4T instead, where its sets are drawn fresh. */
#define COST_SETS_DIRECT_MAX 16384
#define COST_SETS_SMALL 4096

/* How a set is drawn: whole for a pixel (sampler_draw_at), as a light's stream refills
   (stream_refill), or as a padded slot (padding_fill). */
enum cost_set_use { COST_SET_PIXEL, COST_SET_LIGHT, COST_SET_PADDED };

/* The settings a set's cost depends on. */
struct cost_sampler {
    enum sampler_kind kind;
    double threshold;
    int pooled; /* poisson_pool > 0: sets from a pool (its size does not change a draw's cost) */
    enum poisson_domain domain;
};

/* One set's measured cost (CPU seconds) and its mean points; scaled: from two smaller sets. */
struct cost_set {
    double s_per_set, points;
    int scaled;
};

struct cost_sets;

/* The threshold of kind whose sets hold about `points` points, from threshold t's capacity
   (capacity ~ 1 / t^2); at most 100. */
double cost_sets_threshold_for(enum sampler_kind kind, double t, double points);

/* An empty cache. NULL on no memory. Free with cost_sets_free (accepts NULL). */
struct cost_sets *cost_sets_new(void);
void cost_sets_free(struct cost_sets *c);

/* The cost of one set of sp drawn as `use`, from the cache, or measured now (about target_s CPU
   seconds; target_s 0: scaled from the cached set of its kind nearest in size when there is one),
   the CPU seconds measuring took added to *spent_s. 0, or -1 with e filled (no memory). */
int cost_sets_get(struct cost_sets *c, const struct cost_sampler *sp, enum cost_set_use use, double target_s,
                  struct cost_set *out, double *spent_s, struct err *e);

#endif
