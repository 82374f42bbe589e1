/* Unbiasedness of the light-sampling mixture, of next-event estimation and of Russian roulette:
   cornell-book3 rendered with light sampling on (rect light + cone toward the sample: true glass
   sphere) and off (pure cosine / BRDF) must converge to the same image, and every shipped scene
   rendered with the mixture, with nee, with nee and roulette and with the mixture and roulette
   likewise. Compared region by region with a noise bound measured from independent renders; a
   10% change of the light's emission must break the same bound. */
#include <stdlib.h>

#include "check.h"
#include "render/render.h"
#include "scenefile/scene_load.h"

#define SIDE 32  /* image side, pixels */
#define REGION 8 /* regions of REGION x REGION pixels: a 4 x 4 grid */
#define NREG (SIDE / REGION)
#define RUNS 16     /* independent renders per setting: their spread measures the noise */
#define K_SIGMA 4.5 /* bound: |difference| <= K_SIGMA standard errors */

struct region_stats {
    double mean[NREG][NREG][3], se[NREG][NREG][3];
};

/* Render the scene SIDE x SIDE RUNS times (seeds seed0, seed0 + 1, ...; 64 samples per pixel,
   one process) with how's light_sampling_off, nee, dims_all and russian_roulette, and reduce it to
   region means over all runs and their standard errors (the spread of the per-run region means
   over sqrt(RUNS)). */
static int render_regions_as(const struct scene_file *sf, struct render_settings how,
                             enum sampler_kind pixel_kind, uint64_t seed0, struct region_stats *out)
{
    struct err e;
    struct camera cam;
    struct sampler *pix = sampler_new(pixel_kind, 12.5, 0, 0, &e);
    struct sampler *light = sampler_new(SAMPLER_RANDOM, 10, 0, 0, &e);
    struct render_ctx *ctx = NULL;
    float *img = malloc(sizeof(float) * 3 * SIDE * SIDE);
    static double run_mean[RUNS][NREG][NREG][3];
    int rc = -1;
    if (!pix || !light || !img || camera_init(&cam, &sf->camera, 1.0, &e) < 0)
        goto done;
    for (int k = 0; k < RUNS; k++) {
        struct render_settings rs = how;
        rs.width = rs.height = SIDE;
        rs.max_depth = 50;
        rs.seed = seed0 + (uint64_t)k;
        render_ctx_free(ctx);
        if (!(ctx = render_ctx_new(sf->scene, &cam, &rs, pix, light, &e)))
            goto done;
        struct render_stats st;
        render_stats_init(&st);
        for (int y = 0; y < SIDE; y++)
            for (int x = 0; x < SIDE; x++)
                render_pixel(ctx, x, y, &img[(y * SIDE + x) * 3], &st);
        for (int ry = 0; ry < NREG; ry++)
            for (int rx = 0; rx < NREG; rx++)
                for (int c = 0; c < 3; c++) {
                    double s = 0;
                    for (int y = ry * REGION; y < (ry + 1) * REGION; y++)
                        for (int x = rx * REGION; x < (rx + 1) * REGION; x++)
                            s += img[(y * SIDE + x) * 3 + c];
                    run_mean[k][ry][rx][c] = s / (REGION * REGION);
                }
    }
    for (int ry = 0; ry < NREG; ry++)
        for (int rx = 0; rx < NREG; rx++)
            for (int c = 0; c < 3; c++) {
                double s = 0, s2 = 0;
                for (int k = 0; k < RUNS; k++) {
                    s += run_mean[k][ry][rx][c];
                    s2 += run_mean[k][ry][rx][c] * run_mean[k][ry][rx][c];
                }
                double mean = s / RUNS, var = (s2 - RUNS * mean * mean) / (RUNS - 1);
                out->mean[ry][rx][c] = mean;
                out->se[ry][rx][c] = sqrt(var > 0 ? var : 0) / sqrt(RUNS);
            }
    rc = 0;
done:
    render_ctx_free(ctx);
    sampler_free(pix);
    sampler_free(light);
    free(img);
    return rc;
}

static int regions_apart(const struct region_stats *a, const struct region_stats *b, double *worst);

/* render_regions_as with random pixel sets and every decision from the path's rng. */
static int render_regions(const struct scene_file *sf, int light_sampling_off, int nee, int roulette,
                          uint64_t seed0, struct region_stats *out)
{
    const struct render_settings how = {.light_sampling_off = light_sampling_off,
                                        .integrator = (enum integrator)nee,
                                        .russian_roulette = roulette};
    return render_regions_as(sf, how, SAMPLER_RANDOM, seed0, out);
}

/* a and b's regions apart (regions_apart): printed as "scene: what: ...", and checked to be none */
static void check_agree(const char *scene, const char *what, const struct region_stats *a,
                        const struct region_stats *b)
{
    double worst;
    int apart = regions_apart(a, b, &worst);
    printf("%s: %s: %d of %d region-channels over %g sigma, worst %.2f sigma\n", scene, what, apart,
           NREG * NREG * 3, K_SIGMA, worst);
    CHECK(apart == 0);
}

/* Regions (of NREG^2 x 3 channels) whose means differ by more than K_SIGMA combined errors;
 *worst is the largest difference in units of that error. */
static int regions_apart(const struct region_stats *a, const struct region_stats *b, double *worst)
{
    int apart = 0;
    *worst = 0;
    for (int ry = 0; ry < NREG; ry++)
        for (int rx = 0; rx < NREG; rx++)
            for (int c = 0; c < 3; c++) {
                double d = fabs(a->mean[ry][rx][c] - b->mean[ry][rx][c]);
                double se = sqrt(a->se[ry][rx][c] * a->se[ry][rx][c] + b->se[ry][rx][c] * b->se[ry][rx][c]);
                double z = se > 0 ? d / se : (d > 0 ? INFINITY : 0);
                *worst = z > *worst ? z : *worst;
                apart += z > K_SIGMA;
            }
    return apart;
}

int main(void)
{
    struct scene_file sf;
    struct err e;
    static struct region_stats on, off, dim;
    if (scene_load("scenes/cornell-book3.yaml", &sf, &e) < 0) {
        fprintf(stderr, "%s:%d: %s\n", e.file, e.line, e.msg);
        CHECK(0);
        return check_report("test_light_sampling");
    }
    CHECK(sf.scene->n_lights == 2); /* the rect light and the glass sphere */
    CHECK(render_regions(&sf, 0, 0, 0, 1, &on) == 0);
    CHECK(render_regions(&sf, 1, 0, 0, 1000, &off) == 0);
    double worst;
    int apart = regions_apart(&on, &off, &worst);
    printf("light sampling on vs off: %d of %d region-channels over %g sigma, worst %.2f sigma\n", apart,
           NREG * NREG * 3, K_SIGMA, worst);
    CHECK(apart == 0);
    /* Sensitivity: the same bound separates a light 10% dimmer (light sampling on both times). */
    for (int i = 0; i < sf.scene->n_materials; i++)
        if (sf.scene->materials[i].type == MAT_LIGHT)
            sf.scene->materials[i].emit = v3_scale(sf.scene->materials[i].emit, 0.9);
    CHECK(render_regions(&sf, 0, 0, 0, 2000, &dim) == 0);
    int dim_apart = regions_apart(&on, &dim, &worst);
    printf("light 10%% dimmer: %d of %d region-channels over %g sigma, worst %.2f sigma\n", dim_apart,
           NREG * NREG * 3, K_SIGMA, worst);
    CHECK(dim_apart >= NREG * NREG * 3 / 4);
    scene_file_free(&sf);
    /* next-event estimation with MIS against the mixture, scene by scene */
    static const char *const scenes[] = {"checker", "cornell", "cornell-book3", "final"};
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
        char path[64];
        snprintf(path, sizeof path, "scenes/%s.yaml", scenes[i]);
        if (scene_load(path, &sf, &e) < 0) {
            fprintf(stderr, "%s:%d: %s\n", e.file, e.line, e.msg);
            CHECK(0);
            continue;
        }
        static struct region_stats mix, nee, nee_rr, mix_rr, all;
        CHECK(render_regions(&sf, 0, 0, 0, 3000, &mix) == 0);
        CHECK(render_regions(&sf, 0, 1, 0, 4000, &nee) == 0);
        check_agree(scenes[i], "mixture vs nee", &mix, &nee);
        /* Russian roulette with nee (its default) against the mixture and nee without it, and
           with the mixture */
        CHECK(render_regions(&sf, 0, 1, 1, 7000, &nee_rr) == 0);
        check_agree(scenes[i], "mixture vs nee + roulette", &mix, &nee_rr);
        check_agree(scenes[i], "nee vs nee + roulette", &nee, &nee_rr);
        CHECK(render_regions(&sf, 0, 0, 1, 8000, &mix_rr) == 0);
        check_agree(scenes[i], "mixture vs mixture + roulette", &mix, &mix_rr);
        /* sampler_dims: all, every decision from jittered sets, with either integrator (nee
           with roulette: its coin from the sets too) */
        for (int integ = 0; integ < 2; integ++) {
            const struct render_settings how = {
                .integrator = (enum integrator)integ, .dims_all = 1, .russian_roulette = integ};
            CHECK(render_regions_as(&sf, how, SAMPLER_JITTER, 5000 + 1000 * (uint64_t)integ, &all) == 0);
            check_agree(scenes[i],
                        integ ? "mixture vs nee + roulette, sampler_dims all"
                              : "mixture vs mixture, sampler_dims all",
                        &mix, &all);
        }
        scene_file_free(&sf);
    }
    return check_report("test_light_sampling");
}
