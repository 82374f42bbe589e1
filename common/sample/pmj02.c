/* pmj02: progressive multi-jittered (0,2) sequences with best-candidate choice (pmj02.h). Each
   doubling of the sequence first puts a point in the subquadrant diagonally opposite each earlier
   point, then the next doubling fills the other two subquadrants of each quadrant, one of each
   pair chosen at random (Christensen et al. 2018, sec. 3 and 5). Inside its subquadrant a new point
   must avoid every elementary interval already occupied at the new level: its valid x strata
   depend only on the intervals finer in x than the subquadrant, its valid y strata only on those
   finer in y, so both lists are found by descending the interval shapes (Pharr 2019) and any pair
   of them is valid. */
#include "pmj02.h"

#include <stdlib.h>
#include <string.h>

/* The top `bits` bits of v (0 for none). */
static inline uint32_t top(uint32_t v, int bits)
{
    return bits ? v >> (32 - bits) : 0;
}

int pmj02_init(struct pmj02 *w, size_t cap)
{
    int m = 0;
    while (((size_t)1 << m) < cap)
        m++;
    memset(w, 0, sizeof *w);
    w->cap = cap;
    w->candidates = PMJ02_CANDIDATES;
    w->x = malloc(cap * sizeof *w->x);
    w->y = malloc(cap * sizeof *w->y);
    w->occupied = malloc(((size_t)m + 1) * cap);
    w->xs = malloc(cap * sizeof *w->xs);
    w->ys = malloc(cap * sizeof *w->ys);
    w->grid = malloc(2 * cap * sizeof *w->grid);
    w->order = malloc(cap * sizeof *w->order);
    if (!w->x || !w->y || !w->occupied || !w->xs || !w->ys || !w->grid || !w->order) {
        pmj02_release(w);
        return -1;
    }
    return 0;
}

void pmj02_release(struct pmj02 *w)
{
    free(w->x);
    free(w->y);
    free(w->occupied);
    free(w->xs);
    free(w->ys);
    free(w->grid);
    free(w->order);
    memset(w, 0, sizeof *w);
}

/* One placement: level m (2^m points when done), subquadrant (cx, cy) of the 2^g x 2^g grid. */
struct level {
    int m, g;
};

/* Shape k of level m: 2^k columns by 2^(m - k) rows; the flag of the interval holding (x, y). */
static inline uint8_t *interval(const struct pmj02 *w, int m, int k, uint32_t col, uint32_t row)
{
    return w->occupied + ((size_t)k << m) + ((size_t)row << k) + col;
}

static void mark(struct pmj02 *w, int m, uint32_t x, uint32_t y)
{
    for (int k = 0; k <= m; k++)
        *interval(w, m, k, top(x, k), top(y, m - k)) = 1;
}

/* Enter point i at (x, y). */
static void add(struct pmj02 *w, struct level lv, size_t i, uint32_t x, uint32_t y)
{
    w->x[i] = x;
    w->y[i] = y;
    mark(w, lv.m, x, y);
    w->grid[(size_t)top(y, lv.g) << lv.g | top(x, lv.g)] = (uint32_t)i + 1;
}

/* Clear level m's intervals and the g-grid, then enter points [0, count). */
static void relevel(struct pmj02 *w, struct level lv, size_t count)
{
    memset(w->occupied, 0, ((size_t)lv.m + 1) << lv.m);
    memset(w->grid, 0, ((size_t)1 << 2 * lv.g) * sizeof *w->grid);
    for (size_t i = 0; i < count; i++)
        add(w, lv, i, w->x[i], w->y[i]);
}

/* The valid strata of one axis (0 x, 1 y) below prefix (its first `bits` bits, bits >= g) in the
   band of the other axis's subquadrant index `other`: the interval of the shape with `bits` bits on
   this axis and m - bits on the other must be free, and so on down to single strata (bits = m),
   which are appended to out. Returns the count so far. */
static size_t strata(const struct pmj02 *w, struct level lv, int axis, uint32_t prefix, int bits,
                     uint32_t other, uint32_t *out, size_t n)
{
    const uint32_t band = other >> (lv.g - (lv.m - bits));
    const int k = axis ? lv.m - bits : bits; /* the shape's column bits */
    if (*interval(w, lv.m, k, axis ? band : prefix, axis ? prefix : band))
        return n;
    if (bits == lv.m) {
        out[n] = prefix;
        return n + 1;
    }
    n = strata(w, lv, axis, prefix << 1, bits + 1, other, out, n);
    return strata(w, lv, axis, prefix << 1 | 1, bits + 1, other, out, n);
}

/* Squared toroidal distance, in units of 2^-64, from (x, y) to the nearest point in the 5 x 5
   cells of the g-grid around it, or all of a grid of 4 x 4 or less (UINT64_MAX if none): unsigned
   differences read as signed are the shortest way round. */
static uint64_t nearest(const struct pmj02 *w, int g, uint32_t x, uint32_t y)
{
    const uint32_t side = (uint32_t)1 << g, mask = side - 1;
    const uint32_t width = side <= 4 ? side : 5, cx = side <= 4 ? 0 : top(x, g) - 2,
                   cy = side <= 4 ? 0 : top(y, g) - 2;
    uint64_t best = UINT64_MAX;
    for (uint32_t j = 0; j < width; j++)
        for (uint32_t i = 0; i < width; i++) {
            const uint32_t at = w->grid[(size_t)((cy + j) & mask) << g | ((cx + i) & mask)];
            if (!at)
                continue;
            const int64_t ex = (int32_t)(x - w->x[at - 1]), ey = (int32_t)(y - w->y[at - 1]);
            const uint64_t d = (uint64_t)(ex * ex) + (uint64_t)(ey * ey);
            best = d < best ? d : best;
        }
    return best;
}

/* The best of PMJ02_CANDIDATES points in subquadrant (cx, cy) of the 2^g grid at level lv, into
   *x, *y; returns its squared distance to the nearest point so far, or 0 with no valid stratum.
   The valid strata are one x and one y stratum of width 2^-m (Pharr 2019: at each shape the
   earlier net's point takes one of two halves), so the candidates differ in their jitter. */
static uint64_t candidate(const struct pmj02 *w, struct rng *rng, struct level lv, uint32_t cx, uint32_t cy,
                          uint32_t *x, uint32_t *y)
{
    const size_t nx = strata(w, lv, 0, cx, lv.g, cy, w->xs, 0), ny = strata(w, lv, 1, cy, lv.g, cx, w->ys, 0);
    if (!nx || !ny) { /* never seen (test_pmj02 counts them): uniform in the subquadrant */
        *x = cx << (32 - lv.g) | rng_u32(rng) >> lv.g;
        *y = cy << (32 - lv.g) | rng_u32(rng) >> lv.g;
        return 0;
    }
    uint64_t best = 0;
    for (int c = 0; c < w->candidates; c++) {
        const uint32_t sx = w->xs[rng_below(rng, (uint32_t)nx)], sy = w->ys[rng_below(rng, (uint32_t)ny)];
        const uint32_t px = sx << (32 - lv.m) | rng_u32(rng) >> lv.m,
                       py = sy << (32 - lv.m) | rng_u32(rng) >> lv.m;
        const uint64_t d = nearest(w, lv.g, px, py);
        if (c == 0 || d > best) {
            best = d | 1; /* nonzero: found */
            *x = px;
            *y = py;
        }
    }
    return best;
}

/* Point i in subquadrant (cx, cy); returns 0, or -1 if it has no valid stratum. */
static int place(struct pmj02 *w, struct rng *rng, struct level lv, size_t i, uint32_t cx, uint32_t cy)
{
    uint32_t x, y;
    const int found = candidate(w, rng, lv, cx, cy, &x, &y) != 0;
    add(w, lv, i, x, y);
    return found - 1;
}

/* The first n points, in w->x and w->y; returns minus the number of points with no valid stratum. */
static int generate(struct pmj02 *w, struct rng *rng, size_t n)
{
    int dead = 0;
    w->x[0] = rng_u32(rng);
    w->y[0] = rng_u32(rng);
    /* from 4^h points to 2 * 4^h and then 4 * 4^h; the grid of subquadrants is 2^(h+1) square */
    for (int h = 0; ((size_t)1 << 2 * h) < n; h++) {
        const size_t prev = (size_t)1 << 2 * h;
        const int g = h + 1;
        struct level lv = {2 * h + 1, g};
        relevel(w, lv, prev);
        for (size_t i = 0; i < prev; i++)
            w->order[i] = (uint32_t)i;
        for (size_t i = 0; i < prev && prev + i < n; i++) {
            /* the earlier points in a random order: diagonally opposite subquadrants */
            const size_t j = i + rng_below(rng, (uint32_t)(prev - i));
            const uint32_t t = w->order[j];
            w->order[j] = w->order[i];
            w->order[i] = t;
            dead += place(w, rng, lv, prev + i, top(w->x[t], g) ^ 1u, top(w->y[t], g) ^ 1u);
        }
        if (2 * prev >= n)
            break;
        lv.m++;
        relevel(w, lv, 2 * prev);
        /* point i's quadrant still has two subquadrants free, beside it in x and in y: point
           2 prev + i takes the one where its best candidate lies farther from the points so far
           (Christensen et al. choose at random; the (0,2) strata hold either way), then point
           3 prev + i the other */
        for (size_t i = 0; i < prev && 2 * prev + i < n; i++) {
            const uint32_t cx = top(w->x[i], g), cy = top(w->y[i], g);
            uint32_t x[2], y[2];
            const uint64_t d0 = candidate(w, rng, lv, cx ^ 1u, cy, &x[0], &y[0]),
                           d1 = candidate(w, rng, lv, cx, cy ^ 1u, &x[1], &y[1]);
            const uint32_t pick = d1 > d0;
            dead -= !(d0 | d1);
            w->order[i] = pick;
            add(w, lv, 2 * prev + i, x[pick], y[pick]);
        }
        for (size_t i = 0; i < prev && 3 * prev + i < n; i++) {
            const uint32_t beside_x = w->order[i] == 1; /* the other one */
            dead += place(w, rng, lv, 3 * prev + i, top(w->x[i], g) ^ beside_x, top(w->y[i], g) ^ !beside_x);
        }
    }
    return dead;
}

int pmj02_draw(struct pmj02 *w, struct rng *rng, size_t n, struct pt2 *out)
{
    const int dead = generate(w, rng, n);
    for (size_t i = 0; i < n; i++)
        out[i] = (struct pt2){w->x[i] * 0x1.0p-32, w->y[i] * 0x1.0p-32};
    return -dead;
}
