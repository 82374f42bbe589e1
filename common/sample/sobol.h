/* sobol: the Owen-scrambled Sobol (0,2)-sequence, the sobol sampler's points. */
#ifndef SOBOL_H
#define SOBOL_H

#include <stddef.h>
#include <stdint.h>

#include "base/rng.h"
#include "pt2.h"

/* The seeds of one scrambled 2D set: one shuffles the sequence's indices (shared by the pair's two
   dimensions, so the points stay pairs), one scrambles each dimension's digits. */
struct sobol_seeds {
    uint32_t index, x, y;
};

/* The seeds of the next set, three draws of rng: a set per (seed, pixel) and per dimension pair,
   whatever the caller's rng is seeded from. */
struct sobol_seeds sobol_seeds_draw(struct rng *rng);

/* The unscrambled sequence's i-th point as 32-bit binary fractions: x the van der Corput radical
   inverse in base 2, y Sobol's second dimension. */
uint32_t sobol_x(uint32_t i);
uint32_t sobol_y(uint32_t i);

/* Owen's nested uniform scramble of v's binary digits (digit 1 the most significant bit): each
   digit flipped or not by a hash of seed and the digits above it. A bijection of 32-bit values. */
uint32_t sobol_owen(uint32_t v, uint32_t seed);

/* The first n points of the scrambled sequence for seeds s, into out (n <= 2^32). The first 2^m
   points form a (0,m,2)-net for every m; other n are a prefix of one, still stratified at every
   power of two below n. Allocates nothing; cannot fail. */
void sobol_fill(struct sobol_seeds s, size_t n, struct pt2 *out);

/* Point k alone of the scrambled sequence for seeds s: sobol_fill's out[k], bit for bit (for a
   caller that takes a few points of a large set, in any order). Cannot fail. */
struct pt2 sobol_point(struct sobol_seeds s, uint32_t k);

#endif
