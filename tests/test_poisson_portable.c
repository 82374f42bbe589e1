/* test_poisson_portable: the law of Bridson's candidate offsets; and Bridson's sets from the
   SSE2 code (the library's) and from the portable code a machine without SSE2 compiles
   (poisson.c built again here with POISSON_PORTABLE) must be the same, bit for bit: the fixed
   point filter, the four-lane offsets and the sqrt are all exact or correctly rounded, so the
   two paths may not differ by a single point. */
#include <stdlib.h>

#include "check.h"
#include "sample/poisson.h"
#include "sample/sampler.h"

int portable_init(struct poisson *p, double radius, int side, size_t capacity);
void portable_release(struct poisson *p);
size_t portable_draw(struct poisson *p, struct rng *rng, struct pt2 *out, int torus);

#define POISSON_PORTABLE 1
#define poisson_init portable_init
#define poisson_release portable_release
#define poisson_draw portable_draw
#include "../common/sample/poisson.c"
#undef poisson_init
#undef poisson_release
#undef poisson_draw

#include "poisson_same.h"

static const struct poisson_build portable = {portable_init, portable_release, portable_draw};

/* The candidate offsets' law: uniform by area in the annulus [1, 2] (scale 1), every direction
   alike. Checked on 80000 offsets: radii in range, the area median at r^2 = 2.5, the mean at the
   centre, and eight equal sectors of angle (each share within 5 standard errors). */
static void offsets_law(void)
{
    enum { N = 80000 };
    static float ox[N], oy[N];
    uint64_t counter = 12345;
    for (int k = 0; k < N; k += 4)
        poisson_offsets(&counter, 1.0f, ox + k, oy + k);
    int in_range = 1, inner = 0, sector[8] = {0};
    double mx = 0, my = 0;
    for (int k = 0; k < N; k++) {
        double r2 = (double)ox[k] * ox[k] + (double)oy[k] * oy[k];
        in_range &= r2 >= 1 - 1e-5 && r2 <= 4 + 1e-5;
        inner += r2 < 2.5;
        mx += ox[k];
        my += oy[k];
        double a = atan2(oy[k], ox[k]) + POISSON_TWO_PI / 2;
        sector[(int)(a / POISSON_TWO_PI * 8) & 7]++;
    }
    CHECK(in_range);
    double se = sqrt(0.25 / N); /* a half: standard error of a share */
    CHECK_NEAR((double)inner / N, 0.5, 5 * se);
    CHECK_NEAR(mx / N, 0.0, 5 * 1.6 / sqrt(N)); /* |offset| < 2: sd per axis under 1.6 */
    CHECK_NEAR(my / N, 0.0, 5 * 1.6 / sqrt(N));
    double se8 = sqrt(0.125 * 0.875 / N);
    for (int b = 0; b < 8; b++)
        CHECK_NEAR((double)sector[b] / N, 0.125, 5 * se8);
}

int main(void)
{
    poisson_empty_cells_far();
    offsets_law();
    const double thresholds[] = {1, 2.5, 5, 8, 10, 12, 20, 40, 100};
    for (size_t i = 0; i < sizeof thresholds / sizeof thresholds[0]; i++)
        for (int torus = 0; torus <= 1; torus++)
            for (uint64_t seed = 1; seed <= 3; seed++)
                poisson_same(thresholds[i], torus, seed, 3, &portable, NULL);
    return check_report("test_poisson_portable");
}
