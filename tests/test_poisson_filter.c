/* test_poisson_filter: Bridson's fixed point window filter (4 x 4 cells, or 5 x 5 when r is 1.5
   cells or more) only turns down candidates the exact test would turn down too, so the library's
   sets must equal, bit for bit, those of poisson.c built again with no filter at all
   (POISSON_FILTER_WINDOW 0: every candidate takes the exact test), for thresholds whose windows
   are 4, 5 and 6 cells wide, in the square and on the torus. */
#include "check.h"
#include "sample/poisson.h"
#include "sample/sampler.h"

int exact_init(struct poisson *p, double radius, int side, size_t capacity);
void exact_release(struct poisson *p);
size_t exact_draw(struct poisson *p, struct rng *rng, struct pt2 *out, int torus);

#define POISSON_FILTER_WINDOW 0
#define poisson_init exact_init
#define poisson_release exact_release
#define poisson_draw exact_draw
#include "../common/sample/poisson.c"
#undef poisson_init
#undef poisson_release
#undef poisson_draw

#include "poisson_same.h"

static const struct poisson_build exact = {exact_init, exact_release, exact_draw};

int main(void)
{
    poisson_empty_cells_far();
    const double thresholds[] = {1, 2.5, 5, 8, 8.7, 10, 12, 15, 20, 40, 60, 100};
    int seen[8] = {0};
    for (size_t i = 0; i < sizeof thresholds / sizeof thresholds[0]; i++)
        for (int torus = 0; torus <= 1; torus++)
            for (uint64_t seed = 1; seed <= 4; seed++) {
                int window = 0;
                poisson_same(thresholds[i], torus, seed, 5, &exact, &window);
                seen[window < 8 ? window : 7] = 1;
            }
    /* the thresholds above reach every window width the filter handles, and one it does not */
    CHECK(seen[4] && seen[5] && seen[6]);
    return check_report("test_poisson_filter");
}
