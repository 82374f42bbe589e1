/* test_poisson_filter: Bridson's fixed point window filter (4 x 4 cells, or 5 x 5 when r is 1.5
   cells or more) only turns down candidates the exact test would turn down too, so the library's
   sets must equal, bit for bit, those of poisson.c built again with no filter at all
   (POISSON_FILTER_WINDOW 0: every candidate takes the exact test), for thresholds whose windows
   are 4, 5 and 6 cells wide, in the square and on the torus. */
#include <math.h>
#include <stdlib.h>

#include "check.h"
#include "poisson.h"
#include "sampler.h"

int exact_init(struct poisson *p, double radius, int side, size_t capacity);
void exact_release(struct poisson *p);
size_t exact_draw(struct poisson *p, struct rng *rng, struct pt2 *out, int torus);

#define POISSON_FILTER_WINDOW 0
#define poisson_init exact_init
#define poisson_release exact_release
#define poisson_draw exact_draw
#include "../common/poisson.c"
#undef poisson_init
#undef poisson_release
#undef poisson_draw

/* The same construction sampler.c uses for a threshold t (minimum distance t/100); the window
   width into *window. */
static void compare(double t, int torus, uint64_t seed, int *window)
{
    double radius = t / 100.0;
    int side = (int)ceil(1.4142135623730951 * 100.0 / t * (1.0 + 1e-12));
    size_t capacity = (size_t)side * (size_t)side;
    struct poisson lib, exact;
    CHECK(poisson_init(&lib, radius, side, capacity) == 0);
    CHECK(exact_init(&exact, radius, side, capacity) == 0);
    *window = lib.window;
    struct pt2 *a = malloc(capacity * sizeof *a), *b = malloc(capacity * sizeof *b);
    struct rng ra, rb;
    rng_seed(&ra, seed, 5);
    rb = ra;
    size_t n = poisson_draw(&lib, &ra, a, torus);
    size_t m = exact_draw(&exact, &rb, b, torus);
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
    exact_release(&exact);
}

int main(void)
{
    const double thresholds[] = {1, 2.5, 5, 8, 8.7, 10, 12, 15, 20, 40, 60, 100};
    int seen[8] = {0};
    for (size_t i = 0; i < sizeof thresholds / sizeof thresholds[0]; i++)
        for (int torus = 0; torus <= 1; torus++)
            for (uint64_t seed = 1; seed <= 4; seed++) {
                int window = 0;
                compare(thresholds[i], torus, seed, &window);
                seen[window < 8 ? window : 7] = 1;
            }
    /* the thresholds above reach every window width the filter handles, and one it does not */
    CHECK(seen[4] && seen[5] && seen[6]);
    return check_report("test_poisson_filter");
}
