/* poisson_same: does a second build of poisson.c (its init, release and draw under other names)
   draw the library's sets bit for bit? For test_poisson_portable (no SSE2) and
   test_poisson_filter (no fixed point filter). */
#ifndef POISSON_SAME_H
#define POISSON_SAME_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "poisson.h"
#include "sampler.h"

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

#endif
