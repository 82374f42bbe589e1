/* test_compare_spp: samples per pixel to each sampler's threshold (compare_spp.h): exact counts
   for the grid kinds, sobol, halton, pmj02bn and zsobol, the nearest counts named when none is,
   Poisson's expected count. */
#include <math.h>

#include "check.h"
#include "study/load/compare_spp.h"

int main(void)
{
    double t;
    long below, above;
    /* a square: t = 100 / sqrt(spp), and the sampler's own count agrees */
    CHECK(compare_spp_threshold(SAMPLER_JITTER, 16, &t, &below, &above) == 0 && t == 25);
    CHECK(compare_spp_threshold(SAMPLER_UNIFORM, 1, &t, &below, &above) == 0 && t == 100);
    CHECK(compare_spp_threshold(SAMPLER_SOBOL, 9, &t, &below, &above) == 0 && sampler_grid_side(t) == 3 &&
          sampler_capacity(SAMPLER_SOBOL, t) == 9);
    for (long n = 1; n <= 2000; n += 37) { /* every square up to the largest set */
        CHECK(compare_spp_threshold(SAMPLER_HALTON, n * n, &t, &below, &above) == 0 &&
              sampler_capacity(SAMPLER_HALTON, t) == (size_t)(n * n));
    }
    /* not a square: no threshold gives it; the nearest counts are named */
    CHECK(compare_spp_threshold(SAMPLER_JITTER, 10, &t, &below, &above) == -1 && below == 9 && above == 16);
    CHECK(compare_spp_threshold(SAMPLER_RANDOM, 2, &t, &below, &above) == -1 && below == 1 && above == 4);
    /* pmj02bn and zsobol: n x n rounded up to a power of two, so 32 (n = 5) but never 8 or 9 */
    CHECK(compare_spp_threshold(SAMPLER_PMJ02BN, 32, &t, &below, &above) == 0 && t == 20 &&
          sampler_capacity(SAMPLER_PMJ02BN, t) == 32);
    CHECK(compare_spp_threshold(SAMPLER_ZSOBOL, 16, &t, &below, &above) == 0 && t == 25);
    CHECK(compare_spp_threshold(SAMPLER_ZSOBOL, 8, &t, &below, &above) == -1 && below == 4 && above == 16);
    CHECK(compare_spp_threshold(SAMPLER_PMJ02BN, 9, &t, &below, &above) == -1 && below == 4 && above == 16);
    /* poisson: its expected count, about 6150 / t^2 (t = 1 holds about 6145: docs/samplers.md) */
    CHECK(compare_spp_threshold(SAMPLER_POISSON, 6150, &t, &below, &above) == 0 && t == 1);
    CHECK(compare_spp_threshold(SAMPLER_POISSON, 16, &t, &below, &above) == 0 && fabs(t - 19.61) < 1e-9);
    CHECK(compare_spp_threshold(SAMPLER_POISSON, 1, &t, &below, &above) == 0 && t > 0 && t <= 100);
    return check_report("test_compare_spp");
}
