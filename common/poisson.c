/* poisson: Bridson's fast Poisson-disk sampling (SIGGRAPH 2007 sketch) in the unit square or
   on the unit torus, with a background grid reused from draw to draw. */
#include "poisson.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define POISSON_TWO_PI 6.28318530717958647692
/* Bridson's k: candidates tried around an active point before it retires. */
#define POISSON_TRIES 30
/* Candidates generated and checked together; divides POISSON_TRIES. */
#define POISSON_BATCH 3

int poisson_init(struct poisson *s, double radius, int side, size_t capacity)
{
    memset(s, 0, sizeof *s);
    s->radius = radius;
    s->side = side;
    double reach_cells = s->radius * (1.0 + 1e-9) * s->side;
    s->window = (int)ceil(2.0 * reach_cells) + 1;
    s->pad = (int)ceil(reach_cells) + 1;
    s->stride = (size_t)s->side + 2 * (size_t)s->pad;
    for (int k = 0; k < 256; k++) {
        s->dir[k][0] = s->radius * cos(POISSON_TWO_PI * k / 256.0);
        s->dir[k][1] = s->radius * sin(POISSON_TWO_PI * k / 256.0);
    }
    size_t cells = s->stride * s->stride;
    s->cell = malloc(cells * sizeof *s->cell);
    s->cell_u = malloc(cells * sizeof *s->cell_u);
    s->cell_v = malloc(cells * sizeof *s->cell_v);
    s->active = malloc(capacity * sizeof *s->active);
    if (!s->cell || !s->cell_u || !s->cell_v || !s->active) {
        poisson_release(s);
        return -1;
    }
    return 0;
}

void poisson_release(struct poisson *s)
{
    free(s->cell);
    free(s->cell_u);
    free(s->cell_v);
    free(s->active);
    s->cell = s->active = NULL;
    s->cell_u = s->cell_v = NULL;
}

/* Exact test: is (cx, cy) at least r from every sample in the window x window cells from
   (i0, j0)? On the torus distances are taken to the nearest image. No branch per cell (an empty
   cell reads sample 0, which always exists, and ignores it): a skip would be a coin-flip
   branch, and this runs for every candidate that is kept. */
static int poisson_far_exact(const struct poisson *s, const struct pt2 *pts, double cx, double cy, int i0,
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
static inline int poisson_far_enough(const struct poisson *s, const struct poisson_frame *f,
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
static void poisson_insert(struct poisson *s, struct pt2 p, int32_t k, int torus)
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
static inline struct pt2 poisson_candidate(const struct poisson *s, struct rng *rng, struct pt2 base)
{
    double rho = sqrt(1.0 + rng_u32(rng) * (3.0 * 0x1.0p-32));
    uint32_t angle = rng_u32(rng);
    const double *d = s->dir[angle >> 24];
    double t = (angle & 0xffffffu) * (POISSON_TWO_PI * 0x1.0p-32), t2 = t * t;
    double sin_t = t + t * t2 * (-1.0 / 6 + t2 * (1.0 / 120 - t2 * (1.0 / 5040)));
    double cos_t = 1.0 + t2 * (-0.5 + t2 * (1.0 / 24 - t2 * (1.0 / 720)));
    double c = rho * cos_t, sn = rho * sin_t;
    return (struct pt2){base.x + (d[0] * c - d[1] * sn), base.y + (d[1] * c + d[0] * sn)};
}

/* Bridson 2007, "Fast Poisson Disk Sampling in Arbitrary Dimensions": a background grid of
   cells holding at most one sample, an active list, k = 30 candidates uniform by area in the
   annulus [r, 2r] around a random active sample, which retires after k misses. O(N).
   torus != 0 measures distances modulo 1 and wraps candidates into [0, 1). */
size_t poisson_draw(struct poisson *s, struct rng *caller_rng, struct pt2 *out, const int torus)
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
