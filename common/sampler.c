/* sampler: 2D point sets in [0,1)^2 (uniform grid, jitter, random, Bridson Poisson-disk). */
#include "sampler.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SAMPLER_TWO_PI 6.28318530717958647692
#define SAMPLER_SQRT2 1.41421356237309504880
/* Bridson's k: candidates tried around an active point before it retires. */
#define POISSON_TRIES 30
/* Candidates generated and checked together; divides POISSON_TRIES. */
#define POISSON_BATCH 3
/* The pool's own rng stream, so pool sets never correlate with the caller's draws. */
#define POOL_STREAM 0x706f6f6cULL

struct sampler {
    enum sampler_kind kind;
    double threshold;
    int grid_n;      /* uniform/jitter/random: n x n cells */
    size_t capacity; /* sampler_capacity(kind, threshold) */

    /* poisson workspace, allocated once by sampler_new */
    double radius;      /* minimum distance r = threshold / 100 */
    int side;           /* background grid: side x side cells of size 1/side <= r/sqrt(2) */
    int pad;            /* cells of margin around it, so a neighbourhood never leaves the array */
    int window;         /* cells per axis that cover [c - r, c + r] wherever c falls */
    size_t stride;      /* side + 2 pad */
    int32_t *cell;      /* stride^2: index of the sample in a cell, -1 when empty */
    float *cell_u;      /* stride^2 each: that sample's offset inside its cell, in cell widths */
    float *cell_v;      /* (a filter, see poisson_far_enough); 3.4e38 when empty */
    int32_t *active;    /* Bridson's active list: indices into the set being drawn */
    double dir[256][2]; /* r cos, r sin of 2 pi k / 256 */

    /* pool of toroidal Poisson sets, drawn once (pool_size 0: none) */
    int pool_size;
    struct pt2 *pool_pts;
    size_t *pool_start; /* set i is pool_pts[pool_start[i] .. pool_start[i+1]) */
};

static const char *const kind_names[] = {"uniform", "jitter", "random", "poisson"};

int sampler_kind_parse(const char *name, enum sampler_kind *out)
{
    for (int i = 0; i < (int)(sizeof kind_names / sizeof kind_names[0]); i++) {
        if (name && strcmp(name, kind_names[i]) == 0) {
            *out = (enum sampler_kind)i;
            return 0;
        }
    }
    return -1;
}

const char *sampler_kind_name(enum sampler_kind kind)
{
    if ((int)kind < 0 || (int)kind >= (int)(sizeof kind_names / sizeof kind_names[0]))
        return "unknown";
    return kind_names[kind];
}

static int threshold_valid(double threshold)
{
    return threshold > 0.0 && threshold <= 100.0;
}

/* The 1e-9 keeps exact divisors exact: 100 / 0.1 is 999.9999999999999 in doubles. */
static double grid_side_real(double threshold)
{
    return floor(100.0 / threshold + 1e-9);
}

/* Background-grid side for radius r: ceil(sqrt(2) / r), nudged up so that rounding can never
   let two points at least r apart share a cell. */
static double poisson_side_real(double threshold)
{
    return ceil(SAMPLER_SQRT2 * 100.0 / threshold * (1.0 + 1e-12));
}

int sampler_grid_side(double threshold)
{
    if (!threshold_valid(threshold))
        return 0;
    double n = grid_side_real(threshold);
    return n >= (double)INT32_MAX ? INT32_MAX : (int)n;
}

/* side * side, saturating at SIZE_MAX. */
static size_t side_squared(double side)
{
    if (side >= 4294967295.0 || side * side >= (double)SIZE_MAX)
        return SIZE_MAX;
    return (size_t)side * (size_t)side;
}

size_t sampler_capacity(enum sampler_kind kind, double threshold)
{
    if (!threshold_valid(threshold))
        return 0;
    if (kind == SAMPLER_POISSON)
        return side_squared(poisson_side_real(threshold));
    return side_squared(grid_side_real(threshold));
}

size_t sampler_set_capacity(const struct sampler *s)
{
    return s->capacity;
}

void sampler_free(struct sampler *s)
{
    if (!s)
        return;
    free(s->cell);
    free(s->cell_u);
    free(s->cell_v);
    free(s->active);
    free(s->pool_pts);
    free(s->pool_start);
    free(s);
}

/* Exact test: is (cx, cy) at least r from every sample in the window x window cells from
   (i0, j0)? On the torus distances are taken to the nearest image. No branch per cell (an empty
   cell reads sample 0, which always exists, and ignores it): a skip would be a coin-flip
   branch, and this runs for every candidate that is kept. */
static int poisson_far_exact(const struct sampler *s, const struct pt2 *pts, double cx, double cy, int i0,
                             int j0, int torus)
{
    const double r2 = s->radius * s->radius;
    const int32_t *row = s->cell + (size_t)(j0 + s->pad) * s->stride + (size_t)(i0 + s->pad);
    int near = 0;
    for (int j = 0; j < s->window; j++, row += s->stride)
        for (int i = 0; i < s->window; i++) {
            int empty = row[i] < 0;
            struct pt2 q = pts[empty ? 0 : row[i]];
            double dx = fabs(cx - q.x), dy = fabs(cy - q.y);
            if (torus) {
                double wx = 1.0 - dx, wy = 1.0 - dy;
                dx = wx < dx ? wx : dx;
                dy = wy < dy ? wy : dy;
            }
            near |= (dx * dx + dy * dy < r2) & !empty;
        }
    return !near;
}

/* Four floats in one vector register (a GCC/Clang extension; without SIMD hardware the compiler
   emits scalar code). */
typedef float poisson_f4 __attribute__((vector_size(16)));
typedef int32_t poisson_i4 __attribute__((vector_size(16)));

/* Whether any lane of a comparison result is set: SSE's movmskps is one instruction where
   extracting and or-ing four lanes is eight. */
#if defined(__SSE__)
#include <xmmintrin.h>
static inline int poisson_any(poisson_i4 m)
{
    return _mm_movemask_ps((__m128)m) != 0;
}
#else
static inline int poisson_any(poisson_i4 m)
{
    return (m[0] | m[1] | m[2] | m[3]) != 0;
}
#endif

static inline poisson_f4 poisson_load4(const float *p)
{
    poisson_f4 x;
    memcpy(&x, p, sizeof x);
    return x;
}

/* Lanes where a sample of 4 cells in a row (offsets u, v) is closer than sqrt(near2) to
   (col[lane], row). */
static inline poisson_i4 poisson_row_near(const float *u, const float *v, poisson_f4 col, float row,
                                          float near2)
{
    poisson_f4 du = col - poisson_load4(u), dv = row - poisson_load4(v);
    return du * du + dv * dv < near2;
}

/* Is some sample of the 4 x 4 cells whose offsets start at u, v closer than sqrt(near2) to
   (cu, cv)? All in cell widths, (cu, cv) measured from the first cell's corner. One row per
   vector, no branch: an empty cell is just far away. */
static inline int poisson_near4(const float *u, const float *v, size_t stride, float cu, float cv,
                                float near2)
{
    const poisson_f4 steps = {0.0f, 1.0f, 2.0f, 3.0f};
    const poisson_f4 col = cu - steps, row = cv - steps;
    poisson_i4 hit = poisson_row_near(u, v, col, row[0], near2) |
                     poisson_row_near(u + stride, v + stride, col, row[1], near2) |
                     poisson_row_near(u + 2 * stride, v + 2 * stride, col, row[2], near2) |
                     poisson_row_near(u + 3 * stride, v + 3 * stride, col, row[3], near2);
    return poisson_any(hit);
}

/* What poisson_far_enough needs, copied into locals once per draw so the compiler keeps them
   in registers instead of reloading them after every store. */
struct poisson_frame {
    double side;        /* cells per unit length */
    double lift;        /* 2 side - r (a hair wider, in cell widths): xs + lift > 0 */
    int lift_cells;     /* 2 side */
    float near2;        /* (r (1 - 1e-5))^2 in cell widths */
    ptrdiff_t stride;   /* cells per row */
    const float *u, *v; /* offsets of cell (0, 0), inside the margin */
    int window;
};

/* Is (cx, cy) at least r from every sample so far? This test is most of Bridson's cost, and
   nearly every candidate fails it, so in the common case (r < 0.086: a 4 x 4 window) a single
   precision test on offsets within cells (errors below 1e-6 relative) turns down those clearly
   too close; the few left are settled exactly. */
static inline int poisson_far_enough(const struct sampler *s, const struct poisson_frame *f,
                                     const struct pt2 *pts, double cx, double cy, int torus)
{
    double xs = cx * f->side, ys = cy * f->side;
    /* the box [c - r, c + r] starts in cell (i0, j0); truncation floors the lifted values */
    int i0 = (int)(xs + f->lift) - f->lift_cells;
    int j0 = (int)(ys + f->lift) - f->lift_cells;
    if (f->window == 4) {
        ptrdiff_t at = (ptrdiff_t)j0 * f->stride + i0;
        if (poisson_near4(f->u + at, f->v + at, (size_t)f->stride, (float)(xs - i0), (float)(ys - j0),
                          f->near2))
            return 0;
    }
    return poisson_far_exact(s, pts, cx, cy, i0, j0, torus);
}

/* Put sample k at p in its cell; on the torus also put its images shifted by whole periods
   into every margin cell they land in, so lookups never wrap. */
static void poisson_insert(struct sampler *s, struct pt2 p, int32_t k, int torus)
{
    const int side = s->side, pad = s->pad;
    int i = (int)(p.x * side), j = (int)(p.y * side);
    i = i > side - 1 ? side - 1 : i;
    j = j > side - 1 ? side - 1 : j;
    float u = (float)(p.x * side - i), v = (float)(p.y * side - j);
    int periods = torus ? pad / side + 1 : 0;
    for (int b = -periods; b <= periods; b++) {
        int jj = j + b * side;
        if (jj < -pad || jj >= side + pad)
            continue;
        for (int a = -periods; a <= periods; a++) {
            int ii = i + a * side;
            if (ii < -pad || ii >= side + pad)
                continue;
            size_t at = (size_t)(jj + pad) * s->stride + (size_t)(ii + pad);
            s->cell[at] = k;
            s->cell_u[at] = u;
            s->cell_v[at] = v;
        }
    }
}

/* Wrap v into [0, 1); v lies in [-2, 3) since candidates are at most 2r <= 2 away. */
static inline double wrap_unit(double v)
{
    while (v < 0.0)
        v += 1.0;
    while (v >= 1.0)
        v -= 1.0;
    return v; /* -1e-18 + 1.0 rounds to 1.0, caught by the second loop */
}

/* A candidate around base, uniform by area in the annulus [r, 2r]: radius sqrt(r^2 + 3 r^2 u),
   angle 2 pi v. The angle's top 8 bits pick a table direction (pre-scaled by r), the other 24
   turn it by t < 2 pi / 256, whose sine and cosine three Taylor terms give to 1e-15 (libm's sin
   and cos, or rejection sampling with its mispredicted branch, would cost more than the rest
   of the algorithm). */
static inline struct pt2 poisson_candidate(const struct sampler *s, struct rng *rng, struct pt2 base)
{
    double rho = sqrt(1.0 + rng_u32(rng) * (3.0 * 0x1.0p-32));
    uint32_t angle = rng_u32(rng);
    const double *d = s->dir[angle >> 24];
    double t = (angle & 0xffffffu) * (SAMPLER_TWO_PI * 0x1.0p-32), t2 = t * t;
    double sin_t = t + t * t2 * (-1.0 / 6 + t2 * (1.0 / 120 - t2 * (1.0 / 5040)));
    double cos_t = 1.0 + t2 * (-0.5 + t2 * (1.0 / 24 - t2 * (1.0 / 720)));
    double c = rho * cos_t, sn = rho * sin_t;
    return (struct pt2){base.x + (d[0] * c - d[1] * sn), base.y + (d[1] * c + d[0] * sn)};
}

/* Bridson 2007, "Fast Poisson Disk Sampling in Arbitrary Dimensions": a background grid of
   cells holding at most one sample, an active list, k = 30 candidates uniform by area in the
   annulus [r, 2r] around a random active sample, which retires after k misses. O(N).
   torus != 0 measures distances modulo 1 and wraps candidates into [0, 1). */
static inline size_t poisson_draw(struct sampler *s, struct rng *caller_rng, struct pt2 *out, const int torus)
{
    const size_t cells = s->stride * s->stride;
    memset(s->cell, 0xff, cells * sizeof *s->cell);     /* -1 */
    memset(s->cell_u, 0x7f, cells * sizeof *s->cell_u); /* 3.4e38: squares to +inf */
    memset(s->cell_v, 0x7f, cells * sizeof *s->cell_v);

    const double side = s->side, r_cells = s->radius * side;
    const size_t origin = (size_t)s->pad * s->stride + (size_t)s->pad;
    const struct poisson_frame frame = {
        .side = side,
        .lift = 2.0 * side - r_cells * (1.0 + 1e-9), /* rounding never hides a sample */
        .lift_cells = 2 * s->side,
        .near2 = (float)(r_cells * r_cells * (1.0 - 1e-5)),
        .stride = (ptrdiff_t)s->stride,
        .u = s->cell_u + origin,
        .v = s->cell_v + origin,
        .window = s->window,
    };
    size_t count = 0, nactive = 0;
    struct rng local = *caller_rng, *rng = &local; /* a copy kept in registers */
    struct pt2 first = {rng_uniform(rng), rng_uniform(rng)};
    out[count] = first;
    poisson_insert(s, first, (int32_t)count, torus);
    s->active[nactive++] = (int32_t)count++;

    while (nactive > 0) {
        uint32_t a = rng_below(rng, (uint32_t)nactive);
        struct pt2 base = out[s->active[a]];
        int found = 0;
        /* Candidates in small batches, checked before any is kept: the same law as one by one
           (the first acceptable one is kept, the rest of its batch forgotten), but independent
           work the processor can overlap. One outside the square becomes base itself, which
           the check turns down, so there is no branch per candidate. */
        for (int k = 0; k < POISSON_TRIES && !found; k += POISSON_BATCH) {
            struct pt2 c[POISSON_BATCH];
            int far[POISSON_BATCH];
            for (int b = 0; b < POISSON_BATCH; b++) {
                c[b] = poisson_candidate(s, rng, base);
                if (torus) {
                    c[b].x = wrap_unit(c[b].x);
                    c[b].y = wrap_unit(c[b].y);
                } else if ((c[b].x < 0.0) | (c[b].x >= 1.0) | (c[b].y < 0.0) | (c[b].y >= 1.0)) {
                    c[b] = base;
                }
            }
            for (int b = 0; b < POISSON_BATCH; b++)
                far[b] = poisson_far_enough(s, &frame, out, c[b].x, c[b].y, torus);
            for (int b = 0; b < POISSON_BATCH && !found; b++) {
                if (!far[b])
                    continue;
                out[count] = c[b];
                poisson_insert(s, c[b], (int32_t)count, torus);
                s->active[nactive++] = (int32_t)count++;
                found = 1;
            }
        }
        if (!found)
            s->active[a] = s->active[--nactive];
    }
    *caller_rng = local;
    return count;
}

/* (i + u) / n kept strictly inside cell i of n (and so below 1) despite rounding. */
static inline double cell_coord(int i, double u, int n)
{
    double v = (i + u) / n;
    while (v >= 1.0 || (int)(v * n) > i)
        v = nextafter(v, 0.0);
    while ((int)(v * n) < i)
        v = nextafter(v, 1.0);
    return v;
}

/* Shift p by o modulo 1, staying in [0, 1) whatever the rounding of the sum. */
static inline double shift_unit(double p, double o)
{
    double v = p + o;
    if (v >= 1.0)
        v -= 1.0;
    return v >= 1.0 ? 0.0 : v;
}

enum sampler_kind sampler_kind_of(const struct sampler *s)
{
    return s->kind;
}

uint32_t sampler_cells(const struct sampler *s)
{
    return s->kind == SAMPLER_POISSON ? 0 : (uint32_t)s->capacity;
}

struct pt2 sampler_cell_point(const struct sampler *s, uint32_t cell, struct rng *rng)
{
    const int n = s->grid_n;
    const int i = (int)(cell % (uint32_t)n), j = (int)(cell / (uint32_t)n);
    switch (s->kind) {
    case SAMPLER_UNIFORM:
        return (struct pt2){(i + 0.5) / n, (j + 0.5) / n};
    case SAMPLER_JITTER: {
        double u = rng_uniform(rng), v = rng_uniform(rng);
        return (struct pt2){cell_coord(i, u, n), cell_coord(j, v, n)};
    }
    default: {
        double u = rng_uniform(rng), v = rng_uniform(rng);
        return (struct pt2){u, v};
    }
    }
}

size_t sampler_draw(struct sampler *s, struct rng *rng, struct pt2 *out)
{
    const int n = s->grid_n;
    size_t count = 0;
    switch (s->kind) {
    case SAMPLER_UNIFORM:
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++)
                out[count++] = (struct pt2){(i + 0.5) / n, (j + 0.5) / n};
        return count;
    case SAMPLER_JITTER:
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                double u = rng_uniform(rng), v = rng_uniform(rng);
                out[count++] = (struct pt2){cell_coord(i, u, n), cell_coord(j, v, n)};
            }
        return count;
    case SAMPLER_RANDOM:
        for (size_t k = 0; k < (size_t)n * (size_t)n; k++) {
            double u = rng_uniform(rng), v = rng_uniform(rng);
            out[count++] = (struct pt2){u, v};
        }
        return count;
    case SAMPLER_POISSON:
        break;
    }
    if (s->pool_size <= 0)
        return poisson_draw(s, rng, out, 0);

    const struct pt2 *src;
    double ox, oy;
    count = sampler_pool_set(s, rng, &src, &ox, &oy);
    for (size_t k = 0; k < count; k++)
        out[k] = sampler_shift(src[k], ox, oy);
    return count;
}

int sampler_is_pooled(const struct sampler *s)
{
    return s->kind == SAMPLER_POISSON && s->pool_size > 0;
}

/* Cranley-Patterson rotation of a pool set: a toroidal set stays Poisson-disk (distances modulo
   1 are unchanged) under any shift modulo 1. */
size_t sampler_pool_set(const struct sampler *s, struct rng *rng, const struct pt2 **pts, double *ox,
                        double *oy)
{
    if (s->kind != SAMPLER_POISSON || s->pool_size <= 0)
        return 0;
    uint32_t pick = rng_below(rng, (uint32_t)s->pool_size);
    *ox = rng_uniform(rng);
    *oy = rng_uniform(rng);
    *pts = s->pool_pts + s->pool_start[pick];
    return s->pool_start[pick + 1] - s->pool_start[pick];
}

struct pt2 sampler_shift(struct pt2 p, double ox, double oy)
{
    return (struct pt2){shift_unit(p.x, ox), shift_unit(p.y, oy)};
}

/* Draw the pool's toroidal sets from pool_seed into one packed array. */
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
        size_t count = poisson_draw(s, &pool_rng, scratch, 1);
        if (used + count > room) {
            size_t grown = room ? room * 2 : count * (size_t)s->pool_size + count / 8 + 1;
            while (grown < used + count)
                grown *= 2;
            struct pt2 *bigger = realloc(s->pool_pts, grown * sizeof *bigger);
            if (!bigger)
                goto fail;
            s->pool_pts = bigger;
            room = grown;
        }
        memcpy(s->pool_pts + used, scratch, count * sizeof *scratch);
        used += count;
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
    if ((int)kind < SAMPLER_UNIFORM || (int)kind > SAMPLER_POISSON) {
        err_set(e, NULL, 0, 0, "sampler: unknown kind %d", (int)kind);
        return NULL;
    }
    if (!threshold_valid(threshold)) {
        err_set(e, NULL, 0, 0, "threshold: must be a number in (0, 100], got %g", threshold);
        return NULL;
    }
    size_t capacity = sampler_capacity(kind, threshold);
    if (capacity > SAMPLER_MAX_POINTS) {
        if (capacity == SIZE_MAX)
            err_set(e, NULL, 0, 0, "threshold %g would make too many points per set (limit %d)", threshold,
                    SAMPLER_MAX_POINTS);
        else
            err_set(e, NULL, 0, 0, "threshold %g would make %s%zu points per set (limit %d)", threshold,
                    kind == SAMPLER_POISSON ? "up to " : "", capacity, SAMPLER_MAX_POINTS);
        return NULL;
    }

    struct sampler *s = calloc(1, sizeof *s);
    if (!s)
        goto oom;
    s->kind = kind;
    s->threshold = threshold;
    s->grid_n = sampler_grid_side(threshold);
    s->capacity = capacity;
    if (kind != SAMPLER_POISSON)
        return s;

    s->radius = threshold / 100.0;
    s->side = (int)poisson_side_real(threshold);
    double reach_cells = s->radius * (1.0 + 1e-9) * s->side;
    s->window = (int)ceil(2.0 * reach_cells) + 1;
    s->pad = (int)ceil(reach_cells) + 1;
    s->stride = (size_t)s->side + 2 * (size_t)s->pad;
    for (int k = 0; k < 256; k++) {
        s->dir[k][0] = s->radius * cos(SAMPLER_TWO_PI * k / 256.0);
        s->dir[k][1] = s->radius * sin(SAMPLER_TWO_PI * k / 256.0);
    }
    size_t cells = s->stride * s->stride;
    s->cell = malloc(cells * sizeof *s->cell);
    s->cell_u = malloc(cells * sizeof *s->cell_u);
    s->cell_v = malloc(cells * sizeof *s->cell_v);
    s->active = malloc(capacity * sizeof *s->active);
    if (!s->cell || !s->cell_u || !s->cell_v || !s->active)
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
