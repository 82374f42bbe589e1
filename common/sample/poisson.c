/* poisson: Bridson's fast Poisson-disk sampling (SIGGRAPH 2007 sketch) in the unit square or
   on the unit torus, with a background grid reused from draw to draw. */
#include "poisson.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/simd.h"
#include "poisson_filter.h"

#define POISSON_TWO_PI 6.28318530717958647692
/* Bridson's k: candidates tried around an active point before it retires. */
#define POISSON_TRIES 30
/* The widest window (in cells) the fixed point filter covers; wider ones (r of 2 cells or more,
   thresholds near 100) take the exact test alone. A test builds this file again with 0 to
   check that the filter never changes a set. */
#ifndef POISSON_FILTER_WINDOW
#define POISSON_FILTER_WINDOW 5
#endif
/* An empty cell's offsets: -4 cells, at least r from any candidate its window tests on each axis
   (the candidate is r or more right of and below the window's first corner, the last cell 4 cells
   on), and under 7 cells from it (r + 1 < 3): at -5 cells a candidate a hair under 3 cells on
   rounded to 3, 8 cells from the first cell's offsets, whose squares summed to 2^31 and wrapped. */
#define POISSON_EMPTY (-4 * POISSON_FIXED)

int poisson_init(struct poisson *s, double radius, int side, size_t capacity)
{
    memset(s, 0, sizeof *s);
    s->radius = radius;
    s->side = side;
    double reach_cells = s->radius * (1.0 + 1e-9) * s->side;
    s->window = (int)ceil(2.0 * reach_cells) + 1;
    s->pad = (int)ceil(reach_cells) + 1;
    s->stride = (size_t)s->side + 2 * (size_t)s->pad;
    size_t cells = s->stride * s->stride;
    s->cell = malloc(cells * sizeof *s->cell);
    s->cell_uv = malloc(2 * cells * sizeof *s->cell_uv);
    s->active = malloc(capacity * sizeof *s->active);
    if (!s->cell || !s->cell_uv || !s->active) {
        poisson_release(s);
        return -1;
    }
    return 0;
}

void poisson_release(struct poisson *s)
{
    free(s->cell);
    free(s->cell_uv);
    free(s->active);
    s->cell = s->active = NULL;
    s->cell_uv = NULL;
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
typedef uint32_t poisson_u4 __attribute__((vector_size(16)));

/* What the tests need, copied into locals once per draw so the compiler keeps them in
   registers instead of reloading them after every store. */
struct poisson_frame {
    double side;       /* cells per unit length */
    double lift;       /* 2 side - r (a hair wider, in cell widths): xs + lift > 0 */
    int lift_cells;    /* 2 side */
    int32_t near2;     /* (r - 4e-4 cells)^2, in fixed point */
    ptrdiff_t stride;  /* cells per row */
    const int16_t *uv; /* offsets of cell (0, 0), inside the margin */
    int window;
    float r_cells; /* r in cell widths */
    float side_f;  /* side */
};

/* Four candidates around a base in cell (bi, bj) at offset (bu, bv) inside it, all in cell
   widths: where they are relative to that cell (lu, lv), whether they lie inside the square,
   and for the fixed point filter the first cell of the window that covers
   [c - r, c + r] (at, from cell (0, 0)) and the candidate's offset from that cell's corner
   (cuv, packed as poisson_near4 wants). Four lanes at once in single precision: (lu, lv) are
   below 4 in magnitude, so their rounding is under 5e-7 of a cell, and a kept candidate is
   defined by them (its position is computed from them in double). */
struct poisson_lanes {
    float lu[4], lv[4];
    int32_t inside[4], at[4];
    uint32_t cuv[4];
};

/* A base in cell widths: its cell (bi, bj), its offset (bu, bv) inside it and the cell's index in
   the frame's grid (at). */
struct poisson_base {
    int bi, bj;
    float bu, bv;
    int32_t at;
};

static inline void poisson_lanes(const struct poisson_frame *f, const float *ox, const float *oy,
                                 struct poisson_base b, struct poisson_lanes *L)
{
    const int bi = b.bi, bj = b.bj;
    const float bu = b.bu, bv = b.bv;
    const int32_t base_at = b.at;
    poisson_f4 dx, dy;
    memcpy(&dx, ox, sizeof dx);
    memcpy(&dy, oy, sizeof dy);
    const poisson_f4 lu = bu + dx, lv = bv + dy;
    const float lo_u = (float)-bi, hi_u = f->side_f - (float)bi;
    const float lo_v = (float)-bj, hi_v = f->side_f - (float)bj;
    const poisson_i4 inside = (lu >= lo_u) & (lu < hi_u) & (lv >= lo_v) & (lv < hi_v);
    /* window start relative to the base cell: floor(l - r), with l - r + 8 > 0 (|l| < 4) */
    const float lift = 8.0f - f->r_cells;
    const poisson_i4 di = __builtin_convertvector(lu + lift, poisson_i4) - 8;
    const poisson_i4 dj = __builtin_convertvector(lv + lift, poisson_i4) - 8;
    const poisson_f4 cu = lu - __builtin_convertvector(di, poisson_f4); /* exact */
    const poisson_f4 cv = lv - __builtin_convertvector(dj, poisson_f4);
    const poisson_i4 qu = __builtin_convertvector(cu * (float)POISSON_FIXED + 0.5f, poisson_i4);
    const poisson_i4 qv = __builtin_convertvector(cv * (float)POISSON_FIXED + 0.5f, poisson_i4);
    const poisson_i4 at = base_at + dj * (int32_t)f->stride + di;
    const poisson_u4 cuv = (poisson_u4)qu | ((poisson_u4)qv << 16);
    memcpy(L->lu, &lu, sizeof lu);
    memcpy(L->lv, &lv, sizeof lv);
    memcpy(L->inside, &inside, sizeof inside);
    memcpy(L->at, &at, sizeof at);
    memcpy(L->cuv, &cuv, sizeof cuv);
}

/* Is (cx, cy) at least r from every sample so far? The fixed point filter first, unless the
   caller has applied it already (each offset rounded to 1/POISSON_FIXED cell, so a distance
   errs by under 3.5e-4 cells and near2 is lowered by more: a candidate it turns down is truly
   too close), then the exact test. */
static inline int poisson_far_enough(const struct poisson *s, const struct poisson_frame *f,
                                     const struct pt2 *pts, double cx, double cy, int torus, int filtered)
{
    double xs = cx * f->side, ys = cy * f->side;
    /* the box [c - r, c + r] starts in cell (i0, j0); truncation floors the lifted values */
    int i0 = (int)(xs + f->lift) - f->lift_cells;
    int j0 = (int)(ys + f->lift) - f->lift_cells;
    if (f->window <= POISSON_FILTER_WINDOW && !filtered) {
        ptrdiff_t at = (ptrdiff_t)j0 * f->stride + i0;
        uint32_t cu = (uint32_t)((xs - i0) * POISSON_FIXED + 0.5),
                 cv = (uint32_t)((ys - j0) * POISSON_FIXED + 0.5);
        if (poisson_near(f->uv + 2 * at, f->stride, cu | cv << 16, f->near2, f->window))
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
    int16_t u = (int16_t)((p.x * side - i) * POISSON_FIXED + 0.5); /* rounded: both are >= 0 */
    int16_t v = (int16_t)((p.y * side - j) * POISSON_FIXED + 0.5);
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
            s->cell_uv[2 * at] = u;
            s->cell_uv[2 * at + 1] = v;
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

/* Four candidate offsets around a sample, uniform by area in the annulus [r, 2r], scaled by
   `scale` (r in cell widths): radius sqrt(1 + 3 u), angle 2 pi v, four lanes at once in single
   precision (errors near 1e-7 of r; the exact test in double decides). One 64-bit draw each:
   u from its top 24 bits, the angle from its low 26, whose top 2 bits pick the quadrant and
   the other 24 the angle f in it. sin and cos of f come from Taylor polynomials around pi/4
   (|g| <= pi/4, truncation below 4e-8): cos f = (cos g - sin g) / sqrt 2, sin f = (sin g + cos g) / sqrt 2, g
   = f - pi/4. libm's sin and cos, or rejection sampling with its mispredicted branch, would cost more than
   the rest of the algorithm. */
static inline void poisson_offsets(uint64_t *counter, float scale, float *ox, float *oy)
{
    /* four independent draws, written out: a loop here would go through memory */
    const uint64_t c0 = *counter, step = 0x9e3779b97f4a7c15ULL;
    const uint64_t a[4] = {rng_mix64(c0), rng_mix64(c0 + step), rng_mix64(c0 + 2 * step),
                           rng_mix64(c0 + 3 * step)};
    *counter = c0 + 4 * step;
    const poisson_i4 ur = {(int32_t)(a[0] >> 40), (int32_t)(a[1] >> 40), (int32_t)(a[2] >> 40),
                           (int32_t)(a[3] >> 40)};
    const poisson_i4 an = {(int32_t)(a[0] & 0x3ffffff), (int32_t)(a[1] & 0x3ffffff),
                           (int32_t)(a[2] & 0x3ffffff), (int32_t)(a[3] & 0x3ffffff)};
    poisson_f4 u = __builtin_convertvector(ur, poisson_f4) * 0x1.0p-24f;
    poisson_f4 rho = 1.0f + 3.0f * u;
#if SIMD_SSE && !defined(POISSON_PORTABLE)
    rho = (poisson_f4)_mm_sqrt_ps((__m128)rho);
#else
    for (int k = 0; k < 4; k++)
        rho[k] = sqrtf(rho[k]);
#endif
    const poisson_i4 quadrant = an >> 24; /* 0..3 */
    const poisson_f4 f =
        __builtin_convertvector(an & 0xffffff, poisson_f4) * (float)(POISSON_TWO_PI / 4 * 0x1.0p-24);
    const poisson_f4 g = f - (float)(POISSON_TWO_PI / 8), g2 = g * g;
    const poisson_f4 sin_g =
        g * (1.0f + g2 * (-1.0f / 6 + g2 * (1.0f / 120 + g2 * (-1.0f / 5040 + g2 * (1.0f / 362880)))));
    const poisson_f4 cos_g =
        1.0f + g2 * (-0.5f + g2 * (1.0f / 24 + g2 * (-1.0f / 720 + g2 * (1.0f / 40320))));
    const float half_sqrt2 = 0.70710678118654752f;
    rho *= half_sqrt2 * scale;
    const poisson_f4 c = (cos_g - sin_g) * rho, s = (sin_g + cos_g) * rho;
    /* turn (c, s) by quadrant quarter turns: (c, s), (-s, c), (-c, -s), (s, -c), on the bits */
    const poisson_u4 q = (poisson_u4)quadrant, odd = -(q & 1u), cb = (poisson_u4)c, sb = (poisson_u4)s;
    poisson_u4 x = (odd & sb) | (~odd & cb), y = (odd & cb) | (~odd & sb);
    x ^= ((q ^ (q >> 1)) & 1u) << 31;
    y ^= (q >> 1) << 31;
    memcpy(ox, &x, sizeof x);
    memcpy(oy, &y, sizeof y);
}

/* Refill the buffer of candidate offsets: they do not depend on the sample they go around, so
   they are made in bulk, where the vector arithmetic runs at full throughput instead of
   waiting on its own latency before every test. */
static inline __attribute__((always_inline)) void poisson_refill(struct poisson *s, uint64_t *counter,
                                                                 float scale)
{
    for (int k = 0; k < POISSON_OFFSETS; k += 4)
        poisson_offsets(counter, scale, s->off_x + k, s->off_y + k);
}

/* Bridson 2007, "Fast Poisson Disk Sampling in Arbitrary Dimensions": a background grid of
   cells holding at most one sample, an active list, k = 30 candidates uniform by area in the
   annulus [r, 2r] around a random active sample, which retires after k misses. O(N).
   torus != 0 measures distances modulo 1 and wraps candidates into [0, 1). */
static inline __attribute__((always_inline)) size_t
draw_window(struct poisson *s, struct rng *caller_rng, struct pt2 *out, const int torus, const int window)
{
    const size_t cells = s->stride * s->stride;
    memset(s->cell, 0xff, cells * sizeof *s->cell); /* -1 */
    for (size_t k = 0; k < 2 * cells; k++)          /* an empty cell's sample lies 5 cells away */
        s->cell_uv[k] = POISSON_EMPTY;

    const double side = s->side, inv_side = 1.0 / side, r_cells = s->radius * side;
    const size_t origin = (size_t)s->pad * s->stride + (size_t)s->pad;
    const struct poisson_frame frame = {
        .side = side,
        .lift = 2.0 * side - r_cells * (1.0 + 1e-9), /* rounding never hides a sample */
        .lift_cells = 2 * s->side,
        .near2 = (int32_t)floor(pow((r_cells - 4e-4) * POISSON_FIXED, 2)),
        .stride = (ptrdiff_t)s->stride,
        .uv = s->cell_uv + 2 * origin,
        .window = window,
        .r_cells = (float)r_cells,
        .side_f = (float)side,
    };
    size_t count = 0, nactive = 0;
    struct rng local = *caller_rng, *rng = &local; /* a copy kept in registers */
    /* the offsets' own stream: SplitMix64 (Steele et al. 2014) over a counter from rng */
    /* one draw a declarator: the operands of | (and an initializer's members) have no order in C */
    const uint64_t counter_hi = rng_u32(rng), counter_lo = rng_u32(rng);
    uint64_t counter = (counter_hi << 32) | counter_lo;
    int next = POISSON_OFFSETS; /* the buffer starts empty */
    const double first_x = rng_uniform(rng), first_y = rng_uniform(rng);
    struct pt2 first = {first_x, first_y};
    out[count] = first;
    poisson_insert(s, first, (int32_t)count, torus);
    s->active[nactive++] = (int32_t)count++;

    while (nactive > 0) {
        uint32_t a = rng_below(rng, (uint32_t)nactive);
        const struct pt2 base = out[s->active[a]];
        /* the base in cell widths: its cell (bi, bj) and its offset (bu, bv) inside it */
        const double bx = base.x * side, by = base.y * side;
        const int bi = (int)bx, bj = (int)by;
        const float bu = (float)(bx - bi), bv = (float)(by - bj);
        const struct poisson_base cell = {bi, bj, bu, bv, bj * (int32_t)frame.stride + bi};
        int found = 0;
        /* Candidates four at a time, in order: the first acceptable one is kept and the rest of
           its four forgotten, the same law as one by one. */
        for (int k = 0; k < POISSON_TRIES && !found; k += 4) {
            if (next == POISSON_OFFSETS) {
                poisson_refill(s, &counter, (float)r_cells);
                next = 0;
            }
            struct poisson_lanes L;
            poisson_lanes(&frame, s->off_x + next, s->off_y + next, cell, &L);
            next += 4;
            const int lanes = POISSON_TRIES - k < 4 ? POISSON_TRIES - k : 4;
            for (int b = 0; b < lanes; b++) {
                const int filtered = L.inside[b] && frame.window <= POISSON_FILTER_WINDOW;
                if (filtered && poisson_near(frame.uv + 2 * (ptrdiff_t)L.at[b], frame.stride, L.cuv[b],
                                             frame.near2, frame.window))
                    continue; /* the common case: clearly too close */
                struct pt2 c = {(bi + (double)L.lu[b]) * inv_side, (bj + (double)L.lv[b]) * inv_side};
                if (torus) {
                    c.x = wrap_unit(c.x);
                    c.y = wrap_unit(c.y);
                } else if ((c.x < 0.0) | (c.x >= 1.0) | (c.y < 0.0) | (c.y >= 1.0)) {
                    continue;
                }
                if (!poisson_far_enough(s, &frame, out, c.x, c.y, torus, filtered))
                    continue;
                out[count] = c;
                poisson_insert(s, c, (int32_t)count, torus);
                s->active[nactive++] = (int32_t)count++;
                found = 1;
                break;
            }
        }
        if (!found)
            s->active[a] = s->active[--nactive];
    }
    *caller_rng = local;
    return count;
}

/* The common window of 4 cells (thresholds up to about 8.6) in its own copy, where the filter's
   width is a constant. */
size_t poisson_draw(struct poisson *s, struct rng *caller_rng, struct pt2 *out, const int torus)
{
    if (s->window == 4)
        return draw_window(s, caller_rng, out, torus, 4);
    return draw_window(s, caller_rng, out, torus, s->window);
}
