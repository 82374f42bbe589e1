/* halton: Halton points (Halton 1960) with scrambled radical inverses (Owen 1995's nested scramble
   in base b, each node's permutation a random affine one: Matousek 1998), indexed per pixel as pbrt-v4's
   HaltonSampler does (Pharr, Jakob and Humphreys, PBR 4th ed., 8.6): the first two dimensions scaled by 2^7
   and 3^5 tile the image, so pixel (x, y) owns the indices whose first base-2 and base-3 digits name x mod
   128 and y mod 243. */
#ifndef HALTON_H
#define HALTON_H

#include <stdint.h>

#include "base/rng.h"
#include "pt2.h"

/* The pixel tile: 2^7 columns by 3^5 rows; pixel sample i has index offset + i * HALTON_STRIDE. */
#define HALTON_TILE_X 128u
#define HALTON_TILE_Y 243u
#define HALTON_STRIDE (HALTON_TILE_X * HALTON_TILE_Y)
/* Base pairs (the first 64 primes): dimension 0 has bases 2 and 3, dimension d > 0 the pair
   1 + (d - 1) mod 31, so dimensions 32, 63, ... reuse bases with scrambles of their own. */
#define HALTON_DIMS 32u

/* The radical inverse of index in base b (2 <= b <= 311, a prime), each digit permuted by a hash of
   seed and the digits before it (a nested scramble), to at least 32 bits: in [0, 1). Cannot fail. */
double halton_radical_inverse(uint32_t base, uint64_t index, uint64_t seed);

/* The smallest index whose first 7 base-2 digits are x mod 128 reversed and first 5 base-3 digits
   y mod 243 reversed (by the Chinese remainder theorem): pixel (x, y)'s first index. */
uint64_t halton_pixel_offset(uint32_t x, uint32_t y);

/* Where one pixel's set lies: the job's seed, the 2D dimension (0: the camera point in the
   pixel), the pixel. */
struct halton_key {
    uint64_t seed;
    uint32_t dim;
    uint32_t x, y;
};

/* Sample i of k's pixel: dimension 0 the point inside the pixel (the radical inverses of the
   index with the 7 and 5 digits that chose the pixel removed), dimension d > 0 the point in its
   pair of bases; every coordinate scrambled by (seed, dim) alone. Cannot fail. */
struct pt2 halton_point(struct halton_key k, uint32_t i);

/* The pixel's first n points. Cannot fail. */
void halton_fill(struct halton_key k, uint32_t n, struct pt2 *out);

#endif
