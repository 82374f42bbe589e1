/* No sampler biases the image: checker renders (a disk light close over the board) with each
   sampler (pixels and lights, and the newer kinds also under sampler_dims: all) at matching
   sample counts agree with a high-sample reference within noise. */
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "render/render.h"
#include "scenefile/scene_load.h"

#define W 32
#define H 24
#define SEEDS 6

/* Mean linear radiance over the whole image and over its lower half (ground: where the
   soft shadow falls), for one sampler setup and seed. */
static int render_means(const struct scene_file *sf, enum sampler_kind kind, double t, int pool, int dims,
                        uint64_t seed, double out[2])
{
    struct err e;
    struct camera cam;
    if (camera_init(&cam, &sf->camera, (double)W / H, &e) < 0)
        return -1;
    struct sampler *pix = sampler_new(kind, t, pool, seed * 7 + 1, &e);
    struct sampler *light = sampler_new(kind, 5, pool, seed * 7 + 2, &e);
    struct render_settings rs = {W, H, 50, seed, 0, 0, dims, 0};
    struct render_ctx *ctx = pix && light ? render_ctx_new(sf->scene, &cam, &rs, pix, light, &e) : NULL;
    int rc = -1;
    if (ctx) {
        struct render_stats st;
        render_stats_init(&st);
        double all = 0, low = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                float c[3];
                render_pixel(ctx, x, y, c, &st);
                double lum = (c[0] + c[1] + c[2]) / 3;
                all += lum;
                if (y >= H / 2)
                    low += lum;
            }
        out[0] = all / (W * H);
        out[1] = low / (W * H / 2);
        rc = 0;
    }
    render_ctx_free(ctx);
    sampler_free(pix);
    sampler_free(light);
    return rc;
}

int main(void)
{
    struct scene_file sf;
    struct err e;
    if (scene_load("scenes/checker.yaml", &sf, &e) < 0) {
        fprintf(stderr, "%s\n", e.msg);
        CHECK(0);
        return check_report("test_unbiased");
    }
    /* Reference: random pixels and lights at 2500 spp, averaged over two seeds. */
    double ref[2] = {0, 0};
    for (int s = 0; s < 2; s++) {
        double m[2];
        CHECK(render_means(&sf, SAMPLER_RANDOM, 2, 0, 0, 1000 + s, m) == 0);
        ref[0] += m[0] / 2;
        ref[1] += m[1] / 2;
    }
    /* ~100 samples per pixel each: grids at t=10; poisson at t=8 gives ~100 points; pmj02bn and
       zsobol at t=11 have 81 rounded up to 128. */
    struct {
        const char *name;
        enum sampler_kind kind;
        double t;
        int pool, dims;
    } cfg[] = {{"uniform", SAMPLER_UNIFORM, 10, 0, 0},      {"jitter", SAMPLER_JITTER, 10, 0, 0},
               {"random", SAMPLER_RANDOM, 10, 0, 0},        {"poisson", SAMPLER_POISSON, 8, 0, 0},
               {"poisson+pool", SAMPLER_POISSON, 8, 16, 0}, {"sobol", SAMPLER_SOBOL, 10, 0, 0},
               {"halton", SAMPLER_HALTON, 10, 0, 0},        {"pmj02bn", SAMPLER_PMJ02BN, 11, 0, 0},
               {"zsobol", SAMPLER_ZSOBOL, 11, 0, 0},        {"halton+dims", SAMPLER_HALTON, 10, 0, 1},
               {"pmj02bn+dims", SAMPLER_PMJ02BN, 11, 0, 1}, {"zsobol+dims", SAMPLER_ZSOBOL, 11, 0, 1}};
    for (size_t c = 0; c < sizeof cfg / sizeof cfg[0]; c++) {
        double sum[2] = {0, 0}, sum2[2] = {0, 0};
        for (int s = 0; s < SEEDS; s++) {
            double m[2] = {0, 0};
            CHECK(render_means(&sf, cfg[c].kind, cfg[c].t, cfg[c].pool, cfg[c].dims, 1 + s, m) == 0);
            for (int k = 0; k < 2; k++) {
                sum[k] += m[k];
                sum2[k] += m[k] * m[k];
            }
        }
        for (int k = 0; k < 2; k++) {
            double mean = sum[k] / SEEDS;
            double sd = sqrt(fmax(0, sum2[k] / SEEDS - mean * mean) * SEEDS / (SEEDS - 1));
            double se = sd / sqrt(SEEDS);
            /* Within 4 standard errors of the seeds' mean, plus 0.5% of the reference for the
               reference's own noise. A radius-1 light spot (the seed's bug) moves the ground
               mean by far more than this. */
            double bound = 4 * se + 0.005 * ref[k];
            printf("%-13s %s mean %.5f ref %.5f |diff| %.5f bound %.5f\n", cfg[c].name,
                   k ? "ground" : "image ", mean, ref[k], fabs(mean - ref[k]), bound);
            CHECK(fabs(mean - ref[k]) < bound);
        }
    }
    scene_file_free(&sf);
    return check_report("test_unbiased");
}
