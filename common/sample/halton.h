/* halton: Halton points (Halton 1960) with random digit permutations (each digit position of each
   dimension's base its own random permutation of the digits, drawn once per job seed and
   dimension and kept in a table: pbrt-v4's RandomizeStrategy::PermuteDigits), indexed per pixel as
   pbrt-v4's HaltonSampler does (Pharr, Jakob and Humphreys, PBR 4th ed., 8.6): the first two
   dimensions scaled by 2^7 and 3^5 tile the image, so pixel (x, y) owns the indices whose first
   base-2 and base-3 digits name x mod 128 and y mod 243. Base 2 keeps Owen's nested scramble
   (sobol.h's hash, no table). */
#ifndef HALTON_H
#define HALTON_H

#include <stddef.h>
#include <stdint.h>

#include "base/rng.h"
#include "pt2.h"

/* The pixel tile: 2^7 columns by 3^5 rows; pixel sample i has index offset + i * HALTON_STRIDE. */
#define HALTON_TILE_X 128u
#define HALTON_TILE_Y 243u
#define HALTON_STRIDE (HALTON_TILE_X * HALTON_TILE_Y)
/* Base pairs (the first 64 primes): dimension 0 has bases 2 and 3, dimension d > 0 the pair
   1 + (d - 1) mod 31, so dimensions 32, 63, ... reuse bases with permutations of their own. */
#define HALTON_DIMS 32u
/* Dimensions whose permutation tables a cache keeps at once (more: it starts over). */
#define HALTON_CACHE_SLOTS 256

/* One base's scramble: the radical inverse's `digits` digits (base^digits >= 2^32), digit
   position j's permutation image times base^(digits - 1 - j) at pw[j * base + digit], and
   tail[j] the sum of pw[k * base] over k >= j (the images of the zero digits past an index's
   last). */
struct halton_digits {
    uint32_t base;
    int digits;
    double scale;  /* base^digits */
    uint64_t span; /* base^digits as an integer: an index's digits past `digits` are dropped */
    const uint64_t *pw, *tail;
};

/* The scrambled radical inverse of index under d: the digits' images as one exact integer over
   base^digits, one correctly rounded division, in [0, 1). Digits past `digits` are dropped. */
static inline double halton_inverse(const struct halton_digits *d, uint64_t index)
{
    const uint64_t b = d->base;
    const uint64_t *pw = d->pw, *tail = d->tail;
    if (index >= d->span)
        index %= d->span;
    uint64_t numerator = 0;
    for (; index; pw += b, tail++) {
        const uint64_t q = index / b;
        numerator += pw[index - q * b];
        index = q;
    }
    const double v = (double)(numerator + *tail) / d->scale;
    return v < 1.0 ? v : 0x1.fffffffffffffp-1;
}

/* The tables of the dimensions met so far for one job seed (a sampler's workspace, one thread). */
struct halton_cache {
    size_t words;  /* uint64 words one dimension's tables take at most */
    uint64_t *mem; /* HALTON_CACHE_SLOTS x words, calloc'ed: pages touched only when used */
    struct halton_slot *slots;
    int used;
};

/* 0, or -1 out of memory (c then released). Release with halton_cache_release (accepts zeroed). */
int halton_cache_init(struct halton_cache *c);
void halton_cache_release(struct halton_cache *c);

/* The scrambled radical inverse of index in base b (3 <= b <= 311, a prime; or 2, Owen's nested
   scramble) for a scramble key, as the sampler computes it, its table built afresh (slow: for
   tests). In [0, 1). Cannot fail. */
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

/* The pixel's first n points. Sample i: dimension 0 the point inside the pixel (the radical
   inverses of the index with the 7 and 5 digits that chose the pixel removed), dimension d > 0
   the point in its pair of bases; every coordinate scrambled by (seed, dim) alone. The same bits
   whatever the cache held before. Cannot fail. */
void halton_fill(struct halton_cache *c, struct halton_key k, uint32_t n, struct pt2 *out);

#endif
