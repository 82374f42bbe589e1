/* padding: sampler_dims: all's per-pixel sets (padding.h). */
#include "padding.h"

#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/simd.h"
#include "draws.h"

size_t padding_slot_points(const struct sampler *s)
{
    /* a set whose count varies (Poisson's, fresh or pooled, and any sampler drawn whole) may fall
   short of the pixel's: room for two */
    const enum sampler_walk w = sampler_walk_of(s);
    return (w == SAMPLER_WALK_WHOLE || w == SAMPLER_WALK_POOL ? 2 : 1) * sampler_set_capacity(s);
}

int padding_init(struct padding *p, struct sampler *s, int slots, struct err *e)
{
    *p = (struct padding){0};
    p->sampler = s;
    p->slots = slots;
    p->slot_cap = padding_slot_points(s);
    const int lazy = sampler_walk_of(s) == SAMPLER_WALK_SOBOL;
    p->wide = simd_avx2();
    if (lazy) {
        p->sobol = malloc((size_t)slots * sizeof *p->sobol);
        p->order = malloc((size_t)slots * p->slot_cap * sizeof *p->order);
        p->identity = malloc(p->slot_cap * sizeof *p->identity);
        for (size_t k = 0; p->identity && k < p->slot_cap; k++)
            p->identity[k] = sobol_bit_reverse((uint32_t)k);
        p->low_bits = 1;
        while (((size_t)1 << p->low_bits) < p->slot_cap)
            p->low_bits++;
        p->low = malloc(((size_t)1 << p->low_bits) * sizeof *p->low);
        if (p->low)
            sobol_low_table(p->low, p->low_bits);
    } else {
        p->pts = malloc((size_t)slots * p->slot_cap * sizeof *p->pts);
    }
    p->gen = calloc((size_t)slots, sizeof *p->gen);
    if ((lazy ? !p->sobol || !p->order || !p->identity || !p->low : !p->pts) || !p->gen) {
        padding_release(p);
        return err_set(e, NULL, 0, 0,
                       "out of memory for sampler_dims: all's point sets (%d of them, %zu points each)",
                       slots, padding_slot_points(s));
    }
    return 0;
}

void padding_release(struct padding *p)
{
    free(p->pts);
    free(p->sobol);
    free(p->order);
    free(p->identity);
    free(p->low);
    free(p->gen);
    *p = (struct padding){0};
}

void padding_pixel(struct padding *p, uint64_t seed, int px, int py, size_t n)
{
    p->seed = seed;
    p->px = px, p->py = py, p->n = n;
    p->pixel++;
}

/* The first n places of a Fisher-Yates shuffle of the have elements (each `size` bytes) at a,
   from r: place k takes a uniformly random element of those not yet placed. One shuffle for both
   kinds of slot, so that a Sobol slot's shuffled indices draw exactly what its shuffled points
   would. */
static inline __attribute__((always_inline)) void shuffle_head(struct rng *r, void *a, size_t size, size_t n,
                                                               size_t have)
{
    /* always inline: each caller's constant size makes the swaps plain loads and stores; the
       state in a local, which the stores cannot alias */
    unsigned char *b = a, t[sizeof(struct pt2)];
    struct rng local = *r;
    for (size_t k = 0; k < n && k < have; k++) {
        size_t j = k + rng_below(&local, (uint32_t)(have - k));
        memcpy(t, b + k * size, size);
        memcpy(b + k * size, b + j * size, size);
        memcpy(b + j * size, t, size);
    }
    *r = local;
}

/* Swap place b[0] with b[j]. */
static inline void swap_with(uint32_t *b, uint32_t j)
{
    const uint32_t t = b[0];
    b[0] = b[j];
    b[j] = t;
}

/* shuffle_head of have indices at a: the same swaps, the draws made a block at a time first
   (draws_below), not one per swap. */
static void shuffle_indices(struct rng *r, uint32_t *a, size_t n, size_t have, int wide)
{
    uint32_t j[64];
    const size_t places = n < have ? n : have;
    for (size_t k = 0; k < places; k += 64) {
        const size_t m = places - k < 64 ? places - k : 64;
        draws_below(r, m, (uint32_t)(have - k), j, wide);
        uint32_t *b = a + k;
        size_t i = 0;
        for (; i + 4 <= m; i += 4) { /* four a turn: one loop test for four swaps */
            swap_with(b + i, j[i]);
            swap_with(b + i + 1, j[i + 1]);
            swap_with(b + i + 2, j[i + 2]);
            swap_with(b + i + 3, j[i + 3]);
        }
        for (; i < m; i++)
            swap_with(b + i, j[i]);
    }
}

/* A Sobol slot: the seeds draw_sobol would take from r, then the first n places of the same
   Fisher-Yates shuffle applied to the points' indices (the same draws of r): padding_point's
   sobol_point of index order[s] is then the point the whole set's shuffle left at place s. (A set
   is never shorter than the pixel's count n; were it, places past it would read the sequence on.) */
static void fill_sobol(struct padding *p, int slot, struct rng *r)
{
    uint32_t *order = p->order + (size_t)slot * p->slot_cap;
    struct sobol_seeds seeds;
    const size_t have = sampler_sobol_set(p->sampler, r, &seeds);
    p->sobol[slot] = sobol_block_of(seeds, p->low_bits);
    memcpy(order, p->identity, p->slot_cap * sizeof *order); /* the indices, bit-reversed */
    shuffle_indices(r, order, p->n, have, p->wide);
}

/* order holds bit-reversed indices, which sobol_block_point starts from. */
struct pt2 padding_sobol_point(const struct padding *p, int slot, uint32_t s)
{
    const uint32_t k_reversed = p->order[(size_t)slot * p->slot_cap + s];
    if (p->wide)
        return sobol_block_point_wide(&p->sobol[slot], p->low, p->low_bits, k_reversed);
    return sobol_block_point(&p->sobol[slot], p->low, p->low_bits, k_reversed);
}

/* Any other sampler: its whole sets until the pixel's count, shuffled. */
static void fill_points(struct padding *p, int slot, struct rng *r)
{
    struct pt2 *pts = p->pts + (size_t)slot * p->slot_cap;
    const size_t n = p->n, cap = sampler_set_capacity(p->sampler);
    size_t have = 0;
    /* halton, zsobol: slot s is dimension 1 + s of the pixel (0 its camera points) */
    struct sampler_at at = {p->seed, p->px, p->py, 1 + (uint32_t)slot};
    while (have < n && have + cap <= p->slot_cap) {
        have += sampler_draw_at(p->sampler, r, &at, pts + have);
        at.dim += (uint32_t)p->slots;
    }
    shuffle_head(r, pts, sizeof *pts, n, have); /* sample s takes a uniformly random point */
    for (size_t k = have; k < n; k++) { /* unreachable for the shipped samplers: a set is never empty */
        pts[k].x = rng_uniform(r);
        pts[k].y = rng_uniform(r);
    }
}

void padding_fill(struct padding *p, int slot)
{
    const uint64_t t0 = p->timed_draw_ns ? clock_ns(CLOCK_MONOTONIC) : 0;
    struct rng r;
    rng_pixel(&r, p->seed, p->px, p->py, 16 + (uint64_t)slot);
    if (p->sobol)
        fill_sobol(p, slot, &r);
    else
        fill_points(p, slot, &r);
    p->gen[slot] = p->pixel;
    if (p->timed_draw_ns)
        *p->timed_draw_ns += clock_ns(CLOCK_MONOTONIC) - t0;
}
