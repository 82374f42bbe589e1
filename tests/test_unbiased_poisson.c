/* test_unbiased_poisson: fresh Poisson sets are unbiased by construction (toroidal, shifted):
   on a near-field rect light, the image mean with Poisson as light sampler, and with Poisson
   under sampler_dims: all + nee, agrees with random's within 4 standard errors over 100 seeds;
   the seed's square sets (poisson_domain: square) do not (issue 26 measured +1.2% and -1.0%).
   pbrt-v4's samplers (halton, pmj02bn, zsobol) pass the same test, as light sampler and under
   sampler_dims: all (issue 30). */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "render/render.h"
#include "scenefile/scene_load.h"

#define SIDE 8
#define SEEDS 100

struct setup {
    const char *name;
    enum sampler_kind pixel, light;
    enum poisson_domain domain;
    int dims; /* sampler_dims: all */
};

/* Mean radiance of one render of setup u with seed (nee, 16 samples a pixel, depth 2: the
   floor's direct light). */
static double render_mean(const struct scene_file *sf, const struct setup *u, uint64_t seed)
{
    struct err e;
    struct camera cam;
    if (camera_init(&cam, &sf->camera, 1.0, &e) < 0)
        return NAN;
    /* random t=25: 16 points; poisson t=20: about 15 */
    struct sampler *pix = sampler_new(u->pixel, u->pixel == SAMPLER_POISSON ? 20 : 25, 0, 0, &e);
    struct sampler *light = sampler_new(u->light, 20, 0, 0, &e);
    struct render_settings rs = {SIDE, SIDE, 2, seed, 0, 1, u->dims, 0};
    struct render_ctx *ctx = NULL;
    double mean = NAN;
    if (pix && light) {
        sampler_set_domain(pix, u->domain);
        sampler_set_domain(light, u->domain);
        ctx = render_ctx_new(sf->scene, &cam, &rs, pix, light, &e);
    }
    if (ctx) {
        struct render_stats st;
        render_stats_init(&st);
        double sum = 0;
        for (int y = 0; y < SIDE; y++)
            for (int x = 0; x < SIDE; x++) {
                float c[3];
                render_pixel(ctx, x, y, c, &st);
                sum += (c[0] + c[1] + c[2]) / 3;
            }
        mean = sum / (SIDE * SIDE);
    }
    render_ctx_free(ctx);
    sampler_free(pix);
    sampler_free(light);
    return mean;
}

/* Mean and standard error of the image mean over `seeds` seeds (seed streams from first). */
static void over_seeds(const struct scene_file *sf, const struct setup *u, uint64_t first, int seeds,
                       double *mean, double *se)
{
    double sum = 0, sum2 = 0;
    for (int s = 0; s < seeds; s++) {
        double m = render_mean(sf, u, first + (uint64_t)s);
        CHECK(isfinite(m));
        sum += m, sum2 += m * m;
    }
    *mean = sum / seeds;
    *se = sqrt(fmax(0, sum2 / seeds - *mean * *mean) / (seeds - 1));
}

/* z of setup u against setup base, `seeds` seeds each (u's from first_u: independent of base's
   when first_u > seeds). */
static double z_seeds(const struct scene_file *sf, const struct setup *u, const struct setup *base, int seeds,
                      uint64_t first_u)
{
    double m, se, mb, seb;
    over_seeds(sf, base, 1, seeds, &mb, &seb);
    over_seeds(sf, u, first_u, seeds, &m, &se);
    const double z = (m - mb) / sqrt(se * se + seb * seb);
    printf("%-26s mean %.5f (se %.5f) against %-14s %.5f (se %.5f): %+.2f%%, z = %+.2f\n", u->name, m, se,
           base->name, mb, seb, 100 * (m / mb - 1), z);
    return z;
}

/* z of setup u against setup base over SEEDS seeds each. */
static double z_against(const struct scene_file *sf, const struct setup *u, const struct setup *base)
{
    return z_seeds(sf, u, base, SEEDS, 1001);
}

int main(void)
{
    struct scene_file sf;
    struct err e;
    if (scene_load("tests/data/near-light.yaml", &sf, &e) < 0) {
        fprintf(stderr, "%s\n", e.msg);
        CHECK(0);
        return check_report("test_unbiased_poisson");
    }
    const struct setup light_random = {"random lights", SAMPLER_RANDOM, SAMPLER_RANDOM, POISSON_TORUS, 0},
                       light_torus = {"poisson lights, torus", SAMPLER_RANDOM, SAMPLER_POISSON, POISSON_TORUS,
                                      0},
                       light_square = {"poisson lights, square", SAMPLER_RANDOM, SAMPLER_POISSON,
                                       POISSON_SQUARE, 0},
                       dims_random = {"random, dims all", SAMPLER_RANDOM, SAMPLER_RANDOM, POISSON_TORUS, 1},
                       dims_torus = {"poisson dims all, torus", SAMPLER_POISSON, SAMPLER_POISSON,
                                     POISSON_TORUS, 1},
                       dims_square = {"poisson dims all, square", SAMPLER_POISSON, SAMPLER_POISSON,
                                      POISSON_SQUARE, 1};
    /* unbiased: within 4 standard errors (alpha about 6e-5 each) */
    CHECK(fabs(z_against(&sf, &light_torus, &light_random)) < 4);
    CHECK(fabs(z_against(&sf, &dims_torus, &dims_random)) < 4);
    /* the control: the seed's square sets are far outside (the test can fail) */
    CHECK(fabs(z_against(&sf, &light_square, &light_random)) > 4);
    CHECK(fabs(z_against(&sf, &dims_square, &dims_random)) > 4);
    static const struct {
        const char *light, *dims;
        enum sampler_kind kind;
    } field[] = {{"halton lights", "halton dims all", SAMPLER_HALTON},
                 {"pmj02bn lights", "pmj02bn dims all", SAMPLER_PMJ02BN},
                 {"zsobol lights", "zsobol dims all", SAMPLER_ZSOBOL}};
    for (size_t i = 0; i < sizeof field / sizeof field[0]; i++) {
        const struct setup lights = {field[i].light, SAMPLER_RANDOM, field[i].kind, POISSON_TORUS, 0},
                           dims = {field[i].dims, field[i].kind, field[i].kind, POISSON_TORUS, 1};
        CHECK(fabs(z_against(&sf, &lights, &light_random)) < 4);
        CHECK(fabs(z_against(&sf, &dims, &dims_random)) < 4);
    }
    /* pmj02bn under sampler_dims: all against sobol's, both stratified (standard errors ~1e-4
       of the mean over 2000 seeds): a fresh pmj02bn sequence's points are not uniform one by one,
       and the sets drawn fresh read +0.07% here (z about +9 at 2000 seeds, +26 at 16000); sets
       with their digits flipped by a random mask are uniform point by point */
    const struct setup pmj_dims = {"pmj02bn dims all", SAMPLER_PMJ02BN, SAMPLER_PMJ02BN, POISSON_TORUS, 1},
                       sobol_dims = {"sobol dims all", SAMPLER_SOBOL, SAMPLER_SOBOL, POISSON_TORUS, 1};
    CHECK(fabs(z_seeds(&sf, &pmj_dims, &sobol_dims, 2000, 100001)) < 4);
    scene_file_free(&sf);
    return check_report("test_unbiased_poisson");
}
