/* stream: a light's points, taken one at a time from sets of the light sampler, each set in a
   random order, a fresh set when one runs out. What the integrator sees is "the next point";
   which sampler makes it, and how, stays here. */
#ifndef STREAM_H
#define STREAM_H

#include <stddef.h>
#include <stdint.h>

#include "base/err.h"
#include "base/rng.h"
#include "sampler.h"
#include "sobol.h"

/* What the streams of one render share: the sampler and its kind's constants, the counters. */
struct stream_source {
    struct sampler *sampler;  /* the light sampler (not owned) */
    enum sampler_walk walk;   /* how its sets are taken point by point */
    struct sampler_grid grid; /* uniform, jitter, random: the cell points' grid */
    size_t cells;             /* indices a set shuffles (0: its points are shuffled whole) */
    uint32_t *identity;       /* 0, 1, 2, ... cells - 1: a fresh shuffle's start, copied */
    uint64_t *sets;           /* non-NULL: counts the sets drawn */
    uint64_t *timed_draw_ns;  /* non-NULL: every set's draw adds its nanoseconds here */
};

/* One light's current set: its points (drawn whole), or the indices of its points (grid cells,
   a pool set's points shifted when taken, a sobol set's points made when taken), n of them,
   next the first not yet taken. */
struct stream {
    struct pt2 *pts;
    uint32_t *cells;
    const struct pool_point *pool; /* pooled: the set and its shift */
    double ox, oy, cos_oy, sin_oy;
    struct sobol_seeds sobol; /* sobol: the set's seeds */
    size_t n, next;
    struct sampler_at at; /* where the next set is drawn (halton, zsobol; set per pixel by the caller) */
};

/* The first dimension of the light sets' points (struct sampler_at): light i's j-th set of a
   pixel is STREAM_LIGHT_DIM + 2^16 i + j, above every pixel set's (0 and the padded slots). */
#define STREAM_LIGHT_DIM (1u << 20)

/* A source over light sampler s (which must outlive it). 0, or -1 with e filled (no memory).
   Release with stream_source_release. */
int stream_source_init(struct stream_source *src, struct sampler *s, struct err *e);
void stream_source_release(struct stream_source *src);

/* A stream of src's points; its buffers sized for src's sets. 0, or -1 (no memory). Release
   with stream_release (which accepts a zeroed stream). */
int stream_init(struct stream *st, const struct stream_source *src);
void stream_release(struct stream *st);

/* Forget the current set (a new pixel): the next point starts a fresh set. */
static inline void stream_restart(struct stream *st)
{
    st->n = st->next = 0;
}

/* Draw a fresh set into st from rng (out of line: once per set). */
void stream_refill(const struct stream_source *src, struct stream *st, struct rng *rng);

/* A pixel uses only part of a set, in order; a grid or Poisson set in generation order would
   then cover only part of the light (a grid's first rows, a Poisson blob around its first
   point) and bias the image, so the set is consumed in a random order: a Fisher-Yates shuffle
   done lazily, one swap per point taken. Every point taken is then uniform, and the set still
   stratifies what is taken of it; what a kind shuffles (cells, indices, or points drawn whole) is
   its enum sampler_walk's (sampler_kind.h; sobol's: BENCH.md "Sobol points").
   The next point of st from rng; when the sampler knows cos and sin of 2 pi y (a pooled set's
   turns, for a disk light's angle), *turn gets them and *turned 1. Inline with the grid kinds'
   cell point: a light point costs no call. */
static inline __attribute__((always_inline)) struct pt2 stream_next(const struct stream_source *src,
                                                                    struct stream *st, struct rng *rng,
                                                                    struct pt2 *turn, int *turned)
{
    const enum sampler_walk walk = src->walk;
    if (st->next >= st->n)
        stream_refill(src, st, rng);
    size_t k = st->next++;
    if (walk == SAMPLER_WALK_FREE)
        return sampler_grid_point(&src->grid, 0, rng);
    size_t j = k + rng_below(rng, (uint32_t)(st->n - k));
    if (st->cells) {
        uint32_t cell = st->cells[j];
        st->cells[j] = st->cells[k];
        st->cells[k] = cell;
        if (walk == SAMPLER_WALK_POOL) {
            /* the shifted point's angle 2 pi (y + oy): the point's own turned by the shift's */
            const struct pt2 t = st->pool[cell].turn;
            *turn = (struct pt2){t.x * st->cos_oy - t.y * st->sin_oy, t.y * st->cos_oy + t.x * st->sin_oy};
            *turned = 1;
            return sampler_shift(st->pool[cell].p, st->ox, st->oy);
        }
        if (walk == SAMPLER_WALK_SOBOL)
            return sobol_point(st->sobol, cell);
        return sampler_grid_point(&src->grid, cell, rng);
    }
    struct pt2 chosen = st->pts[j];
    st->pts[j] = st->pts[k];
    st->pts[k] = chosen;
    return chosen;
}

/* Pooled sets: the pool point each of the count streams would take next if it were the one
   asked next (rng's next draw picks it), fetched into the cache now. One of them is the next
   point taken unless its set runs out first; without this its load, an L2 hit at the head of
   the path's dependency chain, was about half of a light direction's time. Others: nothing. */
static inline __attribute__((always_inline)) void stream_prefetch(const struct stream_source *src,
                                                                  const struct stream *streams, int count,
                                                                  const struct rng *rng)
{
    if (src->walk != SAMPLER_WALK_POOL)
        return;
    const uint64_t u = rng_peek_u32(rng);
    for (int i = 0; i < count; i++) {
        const struct stream *st = &streams[i];
        if (st->next < st->n) {
            size_t j = st->next + (size_t)((u * (uint32_t)(st->n - st->next)) >> 32);
            __builtin_prefetch(&st->pool[st->cells[j]]);
        }
    }
}

#endif
