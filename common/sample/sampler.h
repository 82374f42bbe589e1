/* sampler: 2D point sets in [0,1)^2 (uniform grid, jitter, random, Bridson Poisson-disk, Owen-scrambled
   Sobol, Owen-scrambled Halton, pmj02bn, Z-Sobol). */
#ifndef SAMPLER_H
#define SAMPLER_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "base/err.h"
#include "base/rng.h"
#include "pt2.h"
#include "sampler_kind.h"

/* Where a fresh Poisson set is drawn (job key poisson_domain): on the unit torus, distances
   measured with wrap-around, then shifted by a random offset modulo 1 (Cranley-Patterson): every
   point uniform, unbiased; or in the unit square without wrap-around, the seed's sets, whose
   density piles up along the edges (docs/samplers.md): kept to reproduce the seed, biased. */
enum poisson_domain { POISSON_TORUS, POISSON_SQUARE };

/* A domain's name; every domain's name in enum order, then NULL (the job key's values). */
const char *poisson_domain_name(enum poisson_domain d);
const char *const *poisson_domain_names(void);

/* The largest set of `kind` taken from a precomputed table (pmj02bn's, pmj02_table.h); larger sets
   are drawn fresh, at another cost per point. 0: the kind keeps no table. */
size_t sampler_table_points(enum sampler_kind kind);

struct sampler;

/* A sampler for (kind, threshold in (0,100]). pool_size > 0 with kind poisson draws that many
   toroidal Poisson sets once from pool_seed (see sampler_draw). Returns NULL and fills e on a bad
   threshold (e.g. a set over SAMPLER_MAX_POINTS) or out of memory. Free with sampler_free. */
struct sampler *sampler_new(enum sampler_kind kind, double threshold, int pool_size, uint64_t pool_seed,
                            struct err *e);
void sampler_free(struct sampler *s);

/* Draw s's fresh Poisson sets in domain d from now on (default POISSON_TORUS). Pools and the
   other kinds ignore it: a pool's sets are toroidal and shifted in either domain. */
void sampler_set_domain(struct sampler *s, enum poisson_domain d);

/* Capacity an `out` array passed to sampler_draw must have. */
size_t sampler_set_capacity(const struct sampler *s);

/* The kind s was made with. */
enum sampler_kind sampler_kind_of(const struct sampler *s);

/* How s's sets are taken point by point (the kind's row of the table in sampler.c; pooled
   Poisson walks its pool). */
enum sampler_walk sampler_walk_of(const struct sampler *s);

/* Sets point by point, for a caller that consumes a set in random order and often only part
   of it (a light's points within one pixel). A uniform, jitter or random set has one point per
   cell of an n x n grid, and that point depends on its cell alone (random: on nothing), so it
   can be made when taken instead of drawing the whole set: sampler_cells is n * n (0 for
   poisson and sobol, whose sets are drawn whole), and sampler_grid_point makes cell c's point,
   distributed exactly as in sampler_draw's set. */
uint32_t sampler_cells(const struct sampler *s);

/* What sampler_grid_point needs of a uniform, jitter or random sampler, to make cell points
   inline (no call, no lookups through the sampler): its kind, its n x n grid, and 2^42 / n + 1,
   which gives a cell's row as a multiply and shift. */
struct sampler_grid {
    enum sampler_kind kind;
    int n;
    uint64_t n_recip;
};
struct sampler_grid sampler_grid_of(const struct sampler *s);

/* (i + u) / n's rounding repair, out of line: v moved to the last double inside cell i of n. */
double sampler_cell_repair(double v, int i, int n);

/* (i + u) / n kept strictly inside cell i of n (and so below 1) despite rounding. */
static inline double sampler_cell_coord(int i, double u, int n)
{
    double v = (i + u) / n;
    if (v < 1.0 && (int)(v * n) == i)
        return v;
    return sampler_cell_repair(v, i, n);
}

/* Cell `cell`'s point of the sampler g = sampler_grid_of(s) describes. cell / n without
   a division: cell < 2^22 (SAMPLER_MAX_POINTS) and n < 2^20, so cell * n_recip / 2^42 exceeds
   cell / n by less than 2^-20 < 1 / n, never reaching the next integer. */
static inline struct pt2 sampler_grid_point(const struct sampler_grid *g, uint32_t cell, struct rng *rng)
{
    const int n = g->n;
    const int j = (int)((cell * g->n_recip) >> 42), i = (int)cell - j * n;
    double u, v;
    switch (g->kind) {
    case SAMPLER_UNIFORM:
        return (struct pt2){(i + 0.5) / n, (j + 0.5) / n};
    case SAMPLER_JITTER:
        rng_uniform_pair(rng, &u, &v);
        return (struct pt2){sampler_cell_coord(i, u, n), sampler_cell_coord(j, v, n)};
    default:
        rng_uniform_pair(rng, &u, &v);
        return (struct pt2){u, v};
    }
}

/* Shift p by o modulo 1, staying in [0, 1) whatever the rounding of the sum (inline: the
   pooled light points take one per point). */
static inline double sampler_shift_unit(double p, double o)
{
    /* v - 1 when v >= 1 by masking 1.0's bits, not by a branch (GCC makes one of `?:` here):
       the wrap is a coin flip, and a light point's branch would wait on the pool's load */
    double v = p + o, one = 1.0, d;
    uint64_t bits;
    memcpy(&bits, &one, sizeof bits);
    bits &= -(uint64_t)(v >= 1.0);
    memcpy(&d, &bits, sizeof d);
    v -= d;
    return v >= 1.0 ? 0.0 : v;
}

/* A pooled point with cos and sin of 2 pi p.y in turn (x, y), for a caller that maps y to an
   angle (a disk light's point): the shifted point's angle 2 pi (y + oy) is then turn rotated by
   2 pi oy, with no sine series per point. Both in one 32-byte record: one cache line a point. */
struct pool_point {
    struct pt2 p, turn;
};
/* A pooled Poisson set without copying it (s poisson with a pool, else 0): the set sampler_draw
   would return for this rng is (*pts)[0 .. count).p each shifted by sampler_shift(p, *ox, *oy);
   returns count and consumes rng exactly as sampler_draw does. */
size_t sampler_pool_set(const struct sampler *s, struct rng *rng, const struct pool_point **pts, double *ox,
                        double *oy);
static inline struct pt2 sampler_shift(struct pt2 p, double ox, double oy)
{
    return (struct pt2){sampler_shift_unit(p.x, ox), sampler_shift_unit(p.y, oy)};
}

/* A sobol set without drawing it (s sobol, else 0): the set sampler_draw would return for this
   rng is sobol_point(*seeds, k) for k in [0, count) (sobol.h); returns count and consumes rng
   exactly as sampler_draw does. For a caller that takes a few points of a set (a light's within
   one pixel): each point then costs only when taken. */
struct sobol_seeds;
size_t sampler_sobol_set(const struct sampler *s, struct rng *rng, struct sobol_seeds *seeds);

/* Where a set is drawn, for the kinds whose points depend on it (halton, zsobol): the job's seed,
   the pixel and the 2D dimension (0 the pixel's camera points, every further set of the pixel a
   dimension of its own). Other kinds ignore it. */
struct sampler_at {
    uint64_t seed;
    int x, y;
    uint32_t dim;
};

/* sampler_draw for the set at `at`: the same for kinds that ignore it; halton and zsobol take
   their points from (at, the point's index) alone and consume nothing of rng, so a pixel's
   point sets are one image-wide sequence's. */
size_t sampler_draw_at(struct sampler *s, struct rng *rng, const struct sampler_at *at, struct pt2 *out);

/* Draw one set into out, consuming rng; returns the count (>= 1). halton and zsobol: the set of
   pixel (0, 0), dimension 0, for a seed drawn from rng (two draws). Allocates nothing: the
   sampler's workspace is reused, so one sampler serves one thread at a time. With a pool,
   the set is one of the pool's, picked by rng and shifted by an rng offset modulo 1
   (Cranley-Patterson rotation). */
size_t sampler_draw(struct sampler *s, struct rng *rng, struct pt2 *out);

#endif
