/* test_poisson_filter: Bridson's fixed point window filter (4 x 4 cells, or 5 x 5 when r is 1.5
   cells or more) only turns down candidates the exact test would turn down too, so the library's
   sets must equal, bit for bit, those of poisson.c built again with no filter at all
   (POISSON_FILTER_WINDOW 0: every candidate takes the exact test), for thresholds whose windows
   are 4, 5 and 6 cells wide, in the square and on the torus. */
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

#include "poisson_same.h"

static const struct poisson_build exact = {exact_init, exact_release, exact_draw};

/* An empty cell is never near. Its offsets lie a few cells up and left of its corner; the
   farthest candidate the 5-cell window tests sits a hair under r + 1 < 3 cells right of and below
   the window's first corner (r a hair under 2 cells: t = 66.665 on 3 cells a side, or 99.998 on
   2), which rounds to 3 cells on both axes: with the offsets at -5 cells that is (8, 8) cells from
   the first cell's, 2^31 squared and summed, which wraps negative and read as "near". */
static void empty_cells_far(void)
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

int main(void)
{
    empty_cells_far();
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
