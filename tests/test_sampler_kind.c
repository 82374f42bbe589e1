/* test_sampler_kind: the one table of sampler traits and of integrators: names round-trip, set
   sizes, expected counts and the smallest threshold follow each row, and flags say what names did. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "render/integrator.h"
#include "sample/sampler.h"

int main(void)
{
    const char *const *names = sampler_kind_names();
    int n = 0;
    for (; names[n]; n++) {
        enum sampler_kind k;
        CHECK(sampler_kind_parse(names[n], &k) == 0 && (int)k == n);
        CHECK(strcmp(sampler_kind_name(k), names[n]) == 0);
        CHECK(sampler_traits(k) && sampler_traits(k)->name == names[n]);
        /* the smallest threshold (to 4 digits) fits the limit, and one digit step below it does not */
        const double t = sampler_smallest_threshold(k);
        CHECK(sampler_capacity(k, t) <= SAMPLER_MAX_POINTS);
        CHECK(sampler_capacity(k, t - 1e-4) > SAMPLER_MAX_POINTS);
        CHECK(sampler_expected_spp(k, 10) <= (double)sampler_capacity(k, 10));
    }
    CHECK(n == SAMPLER_ZSOBOL + 1);
    CHECK(sampler_traits((enum sampler_kind)n) == NULL);
    enum sampler_kind k;
    CHECK(sampler_kind_parse("Poisson", &k) < 0 && sampler_kind_parse(NULL, &k) < 0);

    /* set sizes at t = 10 (n = 10): n * n, the power of two above, Bridson's 15 x 15 cells */
    CHECK(sampler_capacity(SAMPLER_JITTER, 10) == 100 && sampler_capacity(SAMPLER_HALTON, 10) == 100);
    CHECK(sampler_capacity(SAMPLER_PMJ02BN, 10) == 128 && sampler_capacity(SAMPLER_ZSOBOL, 10) == 128);
    CHECK(sampler_capacity(SAMPLER_POISSON, 10) == 225);
    CHECK_NEAR(sampler_expected_spp(SAMPLER_POISSON, 10), 61.5, 1e-9);
    CHECK(sampler_expected_spp(SAMPLER_SOBOL, 10) == 100);
    CHECK(sampler_capacity(SAMPLER_RANDOM, 0) == 0 && sampler_capacity(SAMPLER_RANDOM, 100.5) == 0);
    CHECK(sampler_threshold_valid(100) && !sampler_threshold_valid(0) && !sampler_threshold_valid(NAN));
    CHECK(strcmp(sampler_capacity_unit(SAMPLER_POISSON), "Bridson grid cells") == 0);
    CHECK(strcmp(sampler_capacity_unit(SAMPLER_SOBOL), "points") == 0);
    CHECK(strstr(sampler_count_rule(SAMPLER_ZSOBOL), "power of two") != NULL);
    CHECK(strstr(sampler_count_rule(SAMPLER_HALTON), "power of two") == NULL);

    /* the verdict's sentences by flags: uniform aliases, jitter is the baseline, poisson pools */
    CHECK(sampler_kind_has(SAMPLER_UNIFORM, SAMPLER_ALIASES) &&
          !sampler_kind_has(SAMPLER_JITTER, SAMPLER_ALIASES));
    CHECK(sampler_kind_has(SAMPLER_JITTER, SAMPLER_BASELINE) &&
          !sampler_kind_has(SAMPLER_SOBOL, SAMPLER_BASELINE));
    CHECK(sampler_kind_has(SAMPLER_POISSON, SAMPLER_POOLED) &&
          !sampler_kind_has(SAMPLER_RANDOM, SAMPLER_POOLED));
    char list[256];
    CHECK(strcmp(sampler_kind_list(" | ", list, sizeof list),
                 "uniform | jitter | random | poisson | sobol | halton | pmj02bn | zsobol") == 0);
    CHECK(strcmp(sampler_kind_list(", ", list, 12), "uniform, ji") == 0); /* cut, still ended */

    /* integrators: names in enum order; roulette on by default with next-event estimation only */
    const char *const *in = integrator_names();
    for (int i = 0; in[i]; i++)
        CHECK(strcmp(integrator_traits((enum integrator)i)->name, in[i]) == 0);
    CHECK(integrator_traits(INTEGRATOR_MIXTURE)->roulette == 0 &&
          integrator_traits(INTEGRATOR_NEE)->roulette == 1);
    CHECK(strcmp(integrator_traits(INTEGRATOR_MIXTURE)->hash_tag, "") == 0);
    CHECK(in[0] && in[1] && !in[2]);
    return check_report("test_sampler_kind");
}
