/* pmj02: progressive multi-jittered (0,2) sequences with blue-noise selection (pmj02bn)
   (Christensen, Kensler and Kilpatrick 2018, "Progressive Multi-Jittered Sample Sequences", EGSR),
   their valid strata found as in Pharr 2019 ("Efficient Generation of Points that Satisfy
   Two-Dimensional Elementary Intervals", JCGT 8(1)). */
#ifndef PMJ02_H
#define PMJ02_H

#include <stddef.h>
#include <stdint.h>

#include "base/rng.h"
#include "pt2.h"

/* Best-candidate choices per point (Mitchell 1991): the candidate farthest from the points so far. */
#define PMJ02_CANDIDATES 10

/* The workspace of sequences of up to cap points (cap a power of two, <= 2^24). */
struct pmj02 {
    size_t cap;
    int candidates;    /* PMJ02_CANDIDATES; 1 is plain pmj02 (for comparison) */
    uint32_t *x, *y;   /* the points as 32-bit binary fractions */
    uint8_t *occupied; /* (m + 1) * 2^m flags: elementary intervals of every shape at level m */
    uint32_t *xs, *ys; /* the valid x and y strata of the point being placed */
    uint32_t *grid;    /* point index + 1 per cell of the nearest-neighbour grid, 0 empty */
    uint32_t *order;   /* a shuffle of the previous points */
};

/* Allocate w for sequences of up to cap points. 0, or -1 out of memory (w then released). */
int pmj02_init(struct pmj02 *w, size_t cap);
void pmj02_release(struct pmj02 *w);

/* The first n points (1 <= n <= cap) of a fresh sequence drawn from rng, into out: every prefix of
   2^m points is a (0,m,2)-net (each elementary interval of area 2^-m holds one point), and each
   point is the best of w->candidates valid candidates. Returns the number of points that found no
   valid stratum and were placed uniformly in their subquadrant instead (0 in every test: the
   construction always leaves one). Allocates nothing; cannot fail. */
int pmj02_draw(struct pmj02 *w, struct rng *rng, size_t n, struct pt2 *out);

#endif
