/* padding: sampler_dims: all's per-pixel sets, one per 2D decision ("slot"), each in a random
   order of its own so that the sets of different decisions are not correlated (pbrt's padded
   samplers, Pharr et al., PBR 3rd ed. 7.3 and 7.4). Sample s of a pixel takes point s of each
   slot's set. */
#ifndef PADDING_H
#define PADDING_H

#include <stddef.h>
#include <stdint.h>

#include "base/err.h"
#include "sampler.h"
#include "sobol.h"

/* The sets of one pixel at a time: a slot's set is drawn whole when a sample of the pixel first
   asks for it (from the pixel's own stream for that slot), then shuffled by Fisher-Yates, so
   that sample s takes a uniformly random point of it: a uniform random permutation per pixel and
   slot, whatever the sampler. A Sobol slot keeps its seeds and the shuffled order of its indices
   instead of its points, and makes a point when a sample reads it (sobol_block_point: the same
   bits as the whole set's): most samples end before the deeper slots, whose points then go
   unmade. */
struct padding {
    struct sampler *sampler;   /* the pixel sampler (not owned) */
    int slots;                 /* slots 0 .. slots - 1 */
    size_t slot_cap;           /* points stored per slot */
    struct pt2 *pts;           /* slots x slot_cap */
    struct sobol_block *sobol; /* sobol: each slot's seeds and fixed index part (NULL for the others) */
    uint32_t *order;           /* sobol: slots x slot_cap point indices (bit-reversed), each slot's shuffle */
    uint32_t *identity;        /* sobol: slot_cap indices 0, 1, ... bit-reversed: a fill's start */
    uint64_t *low;             /* sobol: sobol_low_table(low_bits) */
    int low_bits;              /* sobol: the indices' bits (2^low_bits >= slot_cap) */
    int wide;                  /* simd_avx2(): the shuffles' draws and the points with AVX2 */
    uint64_t *gen;             /* slot k is current when gen[k] == pixel */
    uint64_t pixel;            /* bumped by padding_pixel */
    uint64_t seed;             /* the job's seed */
    int px, py;
    size_t n;                /* the pixel's sample count */
    uint64_t *timed_draw_ns; /* non-NULL: every whole-set draw adds its nanoseconds here */
};

/* Points a slot stores for sampler s: a grid's or Sobol's set size; twice a Poisson set's
   capacity, for a fresh Poisson set may hold fewer points than the pixel's and sets are then
   appended until the pixel's count. */
size_t padding_slot_points(const struct sampler *s);

/* Sets up p for `slots` slots (>= 1) of sampler s, which must outlive it.
   0, or -1 with e filled (no memory). Release with padding_release. */
int padding_init(struct padding *p, struct sampler *s, int slots, struct err *e);
void padding_release(struct padding *p);

/* Start pixel (px, py) of a job with seed `seed`, whose pixel set holds n points. */
void padding_pixel(struct padding *p, uint64_t seed, int px, int py, size_t n);

/* Draw slot's whole set for the current pixel (out of line: once per pixel and slot). */
void padding_fill(struct padding *p, int slot);

/* A Sobol slot's point for sample s, made now (out of line: padding_point stays small enough for
   the lanes' unrolled loop, which clang otherwise declines to unroll). */
struct pt2 padding_sobol_point(const struct padding *p, int slot, uint32_t s);

/* Sample s's point of set `slot` (< p->slots) of the current pixel (s < its count n). */
static inline struct pt2 padding_point(struct padding *p, int slot, uint32_t s)
{
    if (p->gen[slot] != p->pixel)
        padding_fill(p, slot);
    if (p->sobol)
        return padding_sobol_point(p, slot, s);
    return p->pts[(size_t)slot * p->slot_cap + s];
}

#endif
