/* poisson_same: does a second build of poisson.c (its init, release and draw under other names)
   draw the library's sets bit for bit? For test_poisson_portable (no SSE2) and
   test_poisson_filter (no fixed point filter). */
#ifndef POISSON_SAME_H
#define POISSON_SAME_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "sample/poisson.h"
#include "sample/sampler.h"

struct poisson_build {
    int (*init)(struct poisson *p, double radius, int side, size_t capacity);
    void (*release)(struct poisson *p);
    size_t (*draw)(struct poisson *p, struct rng *rng, struct pt2 *out, int torus);
};

/* One set at threshold t (minimum distance t/100, the grid sampler.c makes for it), from the
   library and from `other`, seeded alike: the same points, the same count and the rng left in
   the same state. The window width (cells) into *window when window is not NULL. */
static inline void poisson_same(double t, int torus, uint64_t seed, uint64_t stream,
                                const struct poisson_build *other, int *window)
{
    double radius = t / 100.0;
    int side = (int)ceil(1.4142135623730951 * 100.0 / t * (1.0 + 1e-12));
    size_t capacity = (size_t)side * (size_t)side;
    struct poisson lib, alt;
    CHECK(poisson_init(&lib, radius, side, capacity) == 0);
    CHECK(other->init(&alt, radius, side, capacity) == 0);
    if (window)
        *window = lib.window;
    struct pt2 *a = malloc(capacity * sizeof *a), *b = malloc(capacity * sizeof *b);
    struct rng ra, rb;
    rng_seed(&ra, seed, stream);
    rb = ra;
    size_t n = poisson_draw(&lib, &ra, a, torus);
    size_t m = other->draw(&alt, &rb, b, torus);
    int same = n == m && n > 0 && ra.state == rb.state;
    for (size_t k = 0; same && k < n; k++)
        same = a[k].x == b[k].x && a[k].y == b[k].y;
    CHECK(same);
    if (!same)
        fprintf(stderr, "  t=%g torus=%d seed=%llu window %d: %zu vs %zu points\n", t, torus,
                (unsigned long long)seed, lib.window, n, m);
    free(a);
    free(b);
    poisson_release(&lib);
    other->release(&alt);
}

/* An empty cell is never near, in this build's 5-cell filter (poisson.c included before this
   header). Its offsets lie a few cells up and left of its corner; the
   farthest candidate the 5-cell window tests sits a hair under r + 1 < 3 cells right of and below
   the window's first corner (r a hair under 2 cells: t = 66.665 on 3 cells a side, or 99.998 on
   2), which rounds to 3 cells on both axes: with the offsets at -5 cells that is (8, 8) cells from
   the first cell's, 2^31 squared and summed, which wraps negative and read as "near". */
static inline void poisson_empty_cells_far(void)
{
    int16_t uv[2 * 5 * 5];
    for (int k = 0; k < 2 * 5 * 5; k++)
        uv[k] = POISSON_EMPTY;
    const double r_cells = 1.99995;
    const int32_t near2 = (int32_t)floor(pow((r_cells - 4e-4) * POISSON_FIXED, 2));
    const uint32_t far = (uint32_t)((r_cells + 1 - 1e-5) * POISSON_FIXED + 0.5);
    CHECK(far == 3 * POISSON_FIXED);
    CHECK(!poisson_near5(uv, 5, far | far << 16, near2));
    CHECK(!poisson_near5(uv, 5, far, near2));
}

#endif
