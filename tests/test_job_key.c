/* test_job_key: the canonical text every cache key is hashed from: the settings that change
   pixels, in the order and spelling earlier keys used (a change would find no output current). */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "job/job_key.h"

int main(void)
{
    struct job j;
    job_defaults(&j, "jobs/a.yaml");
    char text[512], want[512];
    int n = job_key_text(&j, 32, 24, " ref 0", text, sizeof text);
    snprintf(want, sizeof want, "32x24 random 5 random 5 depth 50 seed 1 pool 0 lights 1 ref 0 worker %s",
             WORKER_VERSION);
    CHECK(strcmp(text, want) == 0 && n == (int)strlen(want));

    /* poisson with next-event estimation, sampler_dims: all (roulette on by the integrator's row) */
    j.sampler = SAMPLER_POISSON;
    j.threshold = 2.5;
    j.integrator = INTEGRATOR_NEE;
    j.dims_all = 1;
    j.poisson_domain = POISSON_SQUARE;
    job_key_text(&j, 8, 8, "", text, sizeof text);
    snprintf(want, sizeof want,
             "8x8 poisson 2.5 random 5 depth 50 seed 1 pool 0 lights 1 worker %s nee dims all poisson square "
             "padded uniformly roulette",
             WORKER_VERSION);
    CHECK(strcmp(text, want) == 0);
    /* the light sampler alone pooling still names the domain; roulette off when said */
    j.sampler = SAMPLER_SOBOL;
    j.light_sampler = SAMPLER_POISSON;
    j.dims_all = 0;
    j.roulette = 0;
    j.poisson_domain = POISSON_TORUS;
    job_key_text(&j, 8, 8, "", text, sizeof text);
    snprintf(want, sizeof want,
             "8x8 sobol 2.5 poisson 5 depth 50 seed 1 pool 0 lights 1 worker %s nee poisson torus",
             WORKER_VERSION);
    CHECK(strcmp(text, want) == 0);
    /* cut to the buffer, the length says so */
    CHECK(job_key_text(&j, 8, 8, "", text, 6) == 5 && strcmp(text, "8x8 s") == 0);
    return check_report("test_job_key");
}
