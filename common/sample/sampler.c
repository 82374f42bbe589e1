/* sampler: 2D point sets in [0,1)^2 (uniform grid, jitter, random, Bridson Poisson-disk, Owen-scrambled
   Sobol, Owen-scrambled Halton, pmj02bn, Z-Sobol). */
#include "sampler.h"

#include "halton.h"
#include "pmj02.h"
#include "pmj02_table.h"
#include "poisson.h"
#include "sobol.h"
#include "zsobol.h"
#include "base/vec3.h"

#include <math.h>
#include <stdlib.h>

/* The pool's own rng stream, so pool sets never correlate with the caller's draws. */
#define POOL_STREAM 0x706f6f6cULL

struct sampler {
    enum sampler_kind kind;
    double threshold;
    int grid_n;                 /* uniform/jitter/random: n x n cells */
    uint64_t n_recip;           /* 2^42 / n + 1: cell / n as a multiply and shift (sampler_grid_point) */
    size_t capacity;            /* sampler_capacity(kind, threshold) */
    enum poisson_domain domain; /* fresh Poisson sets: torus (shifted) or square */

    struct poisson bridson;     /* poisson workspace, allocated once by sampler_new */
    struct pmj02 pmj;           /* pmj02bn workspace, likewise */
    struct halton_cache halton; /* halton: the digit permutations of the dimensions met */
    int log2_count;             /* capacity = 2^log2_count for pmj02bn and zsobol */

    /* pool of toroidal Poisson sets, drawn once (pool_size 0: none) */
    int pool_size;
    struct pool_point *pool; /* the points and their turns */
    size_t *pool_start;      /* set i is pool[pool_start[i] .. pool_start[i+1]) */
};

static const char *const domain_names[] = {"torus", "square", NULL};

const char *const *poisson_domain_names(void)
{
    return domain_names;
}

const char *poisson_domain_name(enum poisson_domain d)
{
    return d == POISSON_SQUARE ? domain_names[1] : domain_names[0];
}

void sampler_set_domain(struct sampler *s, enum poisson_domain d)
{
    s->domain = d;
}

size_t sampler_table_points(enum sampler_kind kind)
{
    return kind == SAMPLER_PMJ02BN ? PMJ02_TABLE_POINTS : 0;
}

size_t sampler_set_capacity(const struct sampler *s)
{
    return s->capacity;
}

void sampler_free(struct sampler *s)
{
    if (!s)
        return;
    poisson_release(&s->bridson);
    pmj02_release(&s->pmj);
    halton_cache_release(&s->halton);
    free(s->pool);
    free(s->pool_start);
    free(s);
}

/* Out of line: the first quotient is almost always inside already, and a call in the loops
   made GCC keep n and the points' values on the stack. */
__attribute__((noinline)) double sampler_cell_repair(double v, int i, int n)
{
    while (v >= 1.0 || (int)(v * n) > i)
        v = nextafter(v, 0.0);
    while ((int)(v * n) < i)
        v = nextafter(v, 1.0);
    return v;
}

enum sampler_kind sampler_kind_of(const struct sampler *s)
{
    return s->kind;
}

uint32_t sampler_cells(const struct sampler *s)
{
    const enum sampler_walk w = sampler_traits(s->kind)->walk;
    return w == SAMPLER_WALK_CELLS || w == SAMPLER_WALK_FREE ? (uint32_t)s->capacity : 0;
}

struct sampler_grid sampler_grid_of(const struct sampler *s)
{
    return (struct sampler_grid){s->kind, s->grid_n, s->n_recip};
}

enum sampler_walk sampler_walk_of(const struct sampler *s)
{
    return s->kind == SAMPLER_POISSON && s->pool_size > 0 ? SAMPLER_WALK_POOL : sampler_traits(s->kind)->walk;
}

/* A prefix of one of the precomputed sequences, its digits flipped by a random mask per
   coordinate (pmj02_table.h): three draws of rng. Sets larger than the table's are drawn fresh. */
static size_t draw_pmj02bn(struct sampler *s, struct rng *rng, struct pt2 *out)
{
    if (s->capacity > PMJ02_TABLE_POINTS) {
        /* fresh, then flipped the same way: a sequence's point k is not uniform by itself (the
           best candidates' choice; +0.07% on a near-field light, BENCH.md), its flipped one is */
        pmj02_draw(&s->pmj, rng, s->capacity, out);
        const uint32_t fx = rng_u32(rng), fy = rng_u32(rng);
        for (size_t k = 0; k < s->capacity; k++)
            out[k] = (struct pt2){(s->pmj.x[k] ^ fx) * 0x1.0p-32, (s->pmj.y[k] ^ fy) * 0x1.0p-32};
        return s->capacity;
    }
    const uint32_t set = rng_below(rng, PMJ02_TABLE_SETS), fx = rng_u32(rng), fy = rng_u32(rng);
    pmj02_table_fill(set, fx, fy, (uint32_t)s->capacity, out);
    return s->capacity;
}

static size_t at_halton(struct sampler *s, const struct sampler_at *at, struct pt2 *out)
{
    halton_fill(&s->halton, (struct halton_key){at->seed, at->dim, (uint32_t)at->x, (uint32_t)at->y},
                (uint32_t)s->capacity, out);
    return s->capacity;
}

static size_t at_zsobol(struct sampler *s, const struct sampler_at *at, struct pt2 *out)
{
    zsobol_fill((struct zsobol_key){at->seed, at->dim, (uint32_t)at->x, (uint32_t)at->y, s->log2_count}, out);
    return s->capacity;
}

/* uniform, jitter, random: a loop each over the n * n cells, row by row (sampler_grid_point makes
   one cell's point alike; one loop through it, its kind switch per point, cost jitter's sets 10%) */
static size_t draw_uniform(struct sampler *s, struct rng *rng, struct pt2 *out)
{
    (void)rng;
    const int n = s->grid_n;
    size_t count = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++)
            out[count++] = (struct pt2){(i + 0.5) / n, (j + 0.5) / n};
    return count;
}

static size_t draw_jitter(struct sampler *s, struct rng *rng, struct pt2 *out)
{
    const int n = s->grid_n;
    size_t count = 0;
    struct rng r = *rng; /* a local state: out may alias *rng, so GCC stored it per point */
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double u, v;
            rng_uniform_pair(&r, &u, &v);
            out[count++] = (struct pt2){sampler_cell_coord(i, u, n), sampler_cell_coord(j, v, n)};
        }
    *rng = r;
    return count;
}

static size_t draw_random(struct sampler *s, struct rng *rng, struct pt2 *out)
{
    const int n = s->grid_n;
    size_t count = 0;
    for (size_t k = 0; k < (size_t)n * (size_t)n; k++) {
        double u, v;
        rng_uniform_pair(rng, &u, &v);
        out[count++] = (struct pt2){u, v};
    }
    return count;
}

/* the first n * n points of a sequence scrambled for this set: a (0,2)-net when n * n is a power
   of two, a net's prefix otherwise (sobol.h) */
static size_t draw_sobol(struct sampler *s, struct rng *rng, struct pt2 *out)
{
    struct sobol_seeds seeds;
    size_t count = sampler_sobol_set(s, rng, &seeds);
    sobol_fill(seeds, count, out);
    return count;
}

static size_t draw_poisson(struct sampler *s, struct rng *rng, struct pt2 *out)
{
    size_t count;
    if (s->pool_size <= 0 && s->domain == POISSON_SQUARE)
        return poisson_draw(&s->bridson, rng, out, 0);
    if (s->pool_size <= 0) {
        /* a toroidal set shifted modulo 1 stays Poisson-disk and makes every point uniform */
        count = poisson_draw(&s->bridson, rng, out, 1);
        const double ox = rng_uniform(rng), oy = rng_uniform(rng);
        for (size_t k = 0; k < count; k++)
            out[k] = sampler_shift(out[k], ox, oy);
        return count;
    }

    const struct pool_point *src;
    double ox, oy;
    count = sampler_pool_set(s, rng, &src, &ox, &oy);
    for (size_t k = 0; k < count; k++)
        out[k] = sampler_shift(src[k].p, ox, oy);
    return count;
}

/* Without a place (worker points, a caller with a stream only): pixel (0, 0), dimension 0, for a
   seed of two draws of rng. */
static size_t at_drawn(struct sampler *s, struct rng *rng, struct pt2 *out);

/* How each kind's set is drawn, in enum sampler_kind's order (its traits: sampler_kind.c): into
   out, consuming rng, at most sampler_capacity points, at least 1. A kind whose points are an
   image-wide sequence's (halton, zsobol) also has an `at` function: the set at (seed, pixel,
   dimension), consuming nothing (sampler_draw_at); its draw is at_drawn. */
static const struct kind_row {
    size_t (*draw)(struct sampler *s, struct rng *rng, struct pt2 *out);
    size_t (*at)(struct sampler *s, const struct sampler_at *at, struct pt2 *out); /* NULL: draw */
} kind_rows[] = {
    {draw_uniform, NULL}, {draw_jitter, NULL},   {draw_random, NULL},  {draw_poisson, NULL},
    {draw_sobol, NULL},   {at_drawn, at_halton}, {draw_pmj02bn, NULL}, {at_drawn, at_zsobol},
};
#define KIND_COUNT ((int)(sizeof kind_rows / sizeof kind_rows[0]))
_Static_assert(KIND_COUNT == SAMPLER_ZSOBOL + 1, "a draw per kind");

static size_t at_drawn(struct sampler *s, struct rng *rng, struct pt2 *out)
{
    uint64_t seed = rng_u32(rng);
    const struct sampler_at at = {seed << 32 | rng_u32(rng), 0, 0, 0};
    return kind_rows[s->kind].at(s, &at, out);
}

size_t sampler_draw(struct sampler *s, struct rng *rng, struct pt2 *out)
{
    return kind_rows[s->kind].draw(s, rng, out);
}

size_t sampler_draw_at(struct sampler *s, struct rng *rng, const struct sampler_at *at, struct pt2 *out)
{
    const struct kind_row *row = &kind_rows[s->kind];
    return row->at ? row->at(s, at, out) : row->draw(s, rng, out);
}

size_t sampler_sobol_set(const struct sampler *s, struct rng *rng, struct sobol_seeds *seeds)
{
    if (s->kind != SAMPLER_SOBOL)
        return 0;
    *seeds = sobol_seeds_draw(rng);
    return (size_t)s->grid_n * (size_t)s->grid_n;
}

/* Cranley-Patterson rotation of a pool set: a toroidal set stays Poisson-disk (distances modulo
   1 are unchanged) under any shift modulo 1. */
size_t sampler_pool_set(const struct sampler *s, struct rng *rng, const struct pool_point **pts, double *ox,
                        double *oy)
{
    if (s->kind != SAMPLER_POISSON || s->pool_size <= 0)
        return 0;
    uint32_t pick = rng_below(rng, (uint32_t)s->pool_size);
    *ox = rng_uniform(rng);
    *oy = rng_uniform(rng);
    *pts = s->pool + s->pool_start[pick];
    return s->pool_start[pick + 1] - s->pool_start[pick];
}

/* Draw the pool's toroidal sets from pool_seed into one packed array of points and their turns. */
static int pool_fill(struct sampler *s, uint64_t pool_seed, struct err *e)
{
    struct rng pool_rng;
    rng_seed(&pool_rng, pool_seed, POOL_STREAM);
    struct pt2 *scratch = malloc(s->capacity * sizeof *scratch);
    s->pool_start = malloc(((size_t)s->pool_size + 1) * sizeof *s->pool_start);
    size_t used = 0, room = 0;
    if (!scratch || !s->pool_start)
        goto fail;
    s->pool_start[0] = 0;
    for (int p = 0; p < s->pool_size; p++) {
        size_t count = poisson_draw(&s->bridson, &pool_rng, scratch, 1);
        if (used + count > room) {
            size_t grown = room ? room * 2 : count * (size_t)s->pool_size + count / 8 + 1;
            while (grown < used + count)
                grown *= 2;
            struct pool_point *bigger = realloc(s->pool, grown * sizeof *bigger);
            if (!bigger)
                goto fail;
            s->pool = bigger;
            room = grown;
        }
        for (size_t k = 0; k < count; k++, used++) {
            s->pool[used].p = scratch[k];
            v3_sincos_turn(scratch[k].y, &s->pool[used].turn.y, &s->pool[used].turn.x);
        }
        s->pool_start[p + 1] = used;
    }
    free(scratch);
    return 0;
fail:
    free(scratch);
    return err_set(e, NULL, 0, 0, "out of memory for a pool of %d Poisson sets", s->pool_size);
}

struct sampler *sampler_new(enum sampler_kind kind, double threshold, int pool_size, uint64_t pool_seed,
                            struct err *e)
{
    if ((int)kind < 0 || (int)kind >= KIND_COUNT) {
        err_set(e, NULL, 0, 0, "sampler: unknown kind %d", (int)kind);
        return NULL;
    }
    if (!sampler_threshold_valid(threshold)) {
        err_set(e, NULL, 0, 0, "threshold: must be a number in (0, 100], got %g", threshold);
        return NULL;
    }
    size_t capacity = sampler_capacity(kind, threshold);
    if (capacity > SAMPLER_MAX_POINTS) {
        if (capacity == SIZE_MAX)
            err_set(e, NULL, 0, 0, "threshold %g would make too many points per set (limit %d)", threshold,
                    SAMPLER_MAX_POINTS);
        else
            err_set(e, NULL, 0, 0, "threshold %g would need %zu %s per set (limit %d)", threshold, capacity,
                    sampler_capacity_unit(kind), SAMPLER_MAX_POINTS);
        return NULL;
    }

    struct sampler *s = calloc(1, sizeof *s);
    if (!s)
        goto oom;
    s->kind = kind;
    s->threshold = threshold;
    s->grid_n = sampler_grid_side(threshold);
    s->n_recip = ((uint64_t)1 << 42) / (uint64_t)s->grid_n + 1;
    s->capacity = capacity;
    while (((size_t)1 << s->log2_count) < capacity)
        s->log2_count++;
    if (kind == SAMPLER_HALTON && halton_cache_init(&s->halton) < 0)
        goto oom;
    if (kind == SAMPLER_PMJ02BN && capacity > PMJ02_TABLE_POINTS && pmj02_init(&s->pmj, capacity) < 0)
        goto oom;
    if (kind != SAMPLER_POISSON)
        return s;

    if (poisson_init(&s->bridson, threshold / 100.0, (int)sampler_poisson_side(threshold), capacity) < 0)
        goto oom;
    if (pool_size > 0) {
        s->pool_size = pool_size;
        if (pool_fill(s, pool_seed, e) != 0)
            goto fail;
    }
    return s;
oom:
    err_set(e, NULL, 0, 0, "out of memory for a %s sampler at threshold %g", sampler_kind_name(kind),
            threshold);
fail:
    sampler_free(s);
    return NULL;
}
