/* test_compare: loading and expanding compare jobs (names, labels, sweeps, references, errors)
   and the statistics drawn from their results; one tiny reference and image rendered, to show that
   a run writes its results and leaves the plan as loaded. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "compare_fixture.h"
#include "study/load/compare_load.h"
#include "study/run/compare.h"
#include "study/run/compare_ref.h"
#include "study/judge/compare_stats.h"
#include "study/present/report_chart.h"
#include "study/present/report_stability.h"
#include "study/judge/verdict_from.h"
#include "base/fileio.h"
#include "image/imgio.h"

static struct compare_fixture fx;

/* A job file written into the scratch folder (compare_fixture_file); its path. */
static const char *job_file(const char *name, const char *text)
{
    return compare_fixture_file(&fx, name, text);
}

static const struct compare_item *item(const struct compare *c, int s, int v, int p, int k)
{
    return &c->items[compare_index(c, s, v, p, k)];
}

static void test_expand(void)
{
    struct err e;
    const char *path = job_file("full.yaml", "name: full\nscenes: [SCENE]\nwidth: 40\n"
                                             "reference: { sampler: jitter, threshold: 2 }\n"
                                             "seeds: [3, 7]\nsweep: { threshold: [20, 10, 5] }\nvariants:\n"
                                             "  - { sampler: poisson, poisson_pool: 64 }\n"
                                             "  - { sampler: jitter, light_sampler: random }\n"
                                             "  - { label: grid, sampler: uniform, max_depth: 4 }\n");
    struct compare *c = compare_load(path, &e);
    CHECK(c != NULL);
    if (!c) {
        fprintf(stderr, "%s:%d:%d: %s\n", e.file, e.line, e.col, e.msg);
        return;
    }
    CHECK(c->n_scenes == 1 && c->n_variants == 3 && c->n_points == 3 && c->n_seeds == 2 && c->n_items == 18);
    CHECK(strcmp(c->name, "full") == 0 && strcmp(c->scenes[0].name, "checker") == 0);
    CHECK(c->scenes[0].width == 40 && c->scenes[0].height == 40); /* the checker camera's aspect is 1 */
    CHECK(strcmp(c->variants[0], "poisson-pool64") == 0);
    CHECK(strcmp(c->variants[1], "jitter-lightrandom") == 0);
    CHECK(strcmp(c->variants[2], "grid") == 0);
    CHECK(strcmp(c->points[1], "threshold 10") == 0 && strcmp(c->sweep_keys, "threshold") == 0);
    const struct compare_item *it = item(c, 0, 0, 2, 1);
    CHECK(strcmp(it->job.output, "checker-poisson-pool64-t5-s7.png") == 0);
    CHECK(it->job.spec.pixel.threshold == 5 && it->job.spec.seed == 7 && it->job.spec.poisson_pool == 64);
    CHECK(it->job.spec.pixel.kind == SAMPLER_POISSON &&
          it->job.spec.light.kind == SAMPLER_POISSON); /* default: same */
    CHECK(strcmp(it->job.name, "full") == 0 && it->job.format == IMG_PNG);
    it = item(c, 0, 1, 0, 0);
    CHECK(strcmp(it->job.output, "checker-jitter-lightrandom-t20-s3.png") == 0);
    CHECK(it->job.spec.light.kind == SAMPLER_RANDOM && it->job.spec.pixel.threshold == 20);
    it = item(c, 0, 2, 1, 0);
    CHECK(strcmp(it->job.output, "checker-grid-t10-s3.png") == 0 && it->job.spec.max_depth == 4);
    CHECK(it->job.spec.max_depth == 4 &&
          item(c, 0, 1, 1, 0)->job.spec.max_depth == 50); /* variants do not leak */
    /* the reference: its settings on the scene, its own seed, rendered at the images' size */
    const struct job *r = &c->scenes[0].ref_job;
    CHECK(c->scenes[0].ref_kind == COMPARE_REF_SETTINGS && r->spec.pixel.kind == SAMPLER_JITTER &&
          r->spec.pixel.threshold == 2);
    CHECK(r->spec.seed == COMPARE_REF_SEED && r->spec.width == 40);
    compare_free(c);
}

static void test_two_keys_no_sweep(void)
{
    struct err e;
    struct compare *c =
        compare_load(job_file("zip.yaml", "scene: SCENE\nwidth: 8\nheight: 6\n"
                                          "sweep: { threshold: [10, 5], light_threshold: [20, 10] }\n"
                                          "variants:\n  - { sampler: random }\n"),
                     &e);
    CHECK(c && c->n_points == 2 && c->n_seeds == 1 && c->n_items == 2); /* swept keys step together */
    if (c) {
        CHECK(strcmp(c->items[1].job.output, "checker-random-t5-lt10-s1.png") == 0);
        CHECK(c->items[1].job.spec.light.threshold == 10 && c->scenes[0].ref_kind == COMPARE_REF_NONE);
        CHECK(strcmp(c->points[1], "threshold 5, light_threshold 10") == 0);
    }
    compare_free(c);
    c = compare_load(
        job_file("plain.yaml", "scene: SCENE\nseed: 9\nvariants:\n  - { sampler: jitter, threshold: 4 }\n"),
        &e);
    CHECK(c && c->n_points == 1 && strcmp(c->points[0], "as set") == 0);
    CHECK(c && strcmp(c->items[0].job.output, "checker-jitter-t4-t4-s9.png") == 0);
    compare_free(c);
}

static void test_errors(void)
{
    struct err e;
    CHECK(!compare_load(job_file("e1.yaml", "scenes: [SCENE]\nvariants:\n  - { sampler: jitter, seed: 4 }\n"),
                        &e));
    CHECK(e.line == 3 && e.col == 24 && strstr(e.msg, "seed: not allowed in a variant: list the seeds once"));
    CHECK(!compare_load(job_file("e2.yaml", "scenes: [SCENE]\nsweep: { threshold: 5 }\nvariants:\n  - {}\n"),
                        &e));
    CHECK(e.line == 2 && e.col == 21 && strstr(e.msg, "threshold: the sweep needs a non-empty list"));
    CHECK(!compare_load(
        job_file("e3.yaml", "scenes: [SCENE]\nvariants:\n  - { label: a }\n  - { label: a }\n"), &e));
    CHECK(e.line == 4 && strstr(e.msg, "two variants are labelled \"a\""));
    CHECK(!compare_load(job_file("e4.yaml", "scenes: []\nvariants:\n  - { sampler: jitter }\n"), &e));
    CHECK(e.line == 1 && e.col == 9 && strstr(e.msg, "scenes: must be a non-empty list"));
    CHECK(!compare_load(job_file("e7.yaml", "scenes: [SCENE]\nrank_by: mode\nvariants:\n  - { label: a }\n"),
                        &e));
    CHECK(e.line == 2 && e.col == 10 && strstr(e.msg, "rank_by: must be mean or median, got mode"));
    {
        struct compare *c = compare_load(
            job_file("m1.yaml", "scenes: [SCENE]\nrank_by: median\nvariants:\n  - { label: a }\n"), &e);
        CHECK(c && c->rank_by == VERDICT_RANK_MEDIAN);
        compare_free(c);
        c = compare_load(job_file("m2.yaml", "scenes: [SCENE]\nvariants:\n  - { label: a }\n"), &e);
        CHECK(c && c->rank_by == VERDICT_RANK_MEAN); /* the default */
        compare_free(c);
    }
    { /* a reference image with a NaN: refused at load, at its line:col, before any render */
        struct rgbf img = {0};
        char path[1100];
        CHECK(image_f_alloc(&img, 4, 4, &e) == 0);
        for (int i = 0; i < 4 * 4 * 3; i++)
            img.px[i] = i == 7 ? NAN : 0.5f;
        snprintf(path, sizeof path, "%s/nan.exr", fx.dir);
        CHECK(imgio_write_f(path, &img, IMG_EXR, NULL, 0, &e) == 0);
        image_f_free(&img);
        CHECK(!compare_load(job_file("e6.yaml", "scene: SCENE\nwidth: 4\nheight: 4\nreference: nan.exr\n"
                                                "variants:\n  - { label: a }\n"),
                            &e));
        CHECK(e.line == 4 && e.col == 12 && strstr(e.msg, "1 of its 48 values are NaN or infinite"));
    }
    CHECK(!compare_load(
        job_file("e5.yaml", "scenes: [SCENE]\nreference: nowhere.png\nvariants:\n  - { label: a }\n"), &e));
    CHECK(e.line == 2 && e.col == 12 && strstr(e.msg, "reference: no image file at"));
}

/* A compare job loaded from yaml (file name, text with SCENE) whose results the test fills by
   hand: its scene's reference counts as an image file. NULL (a failed check) when it does not load. */
static struct compare *hand_made(const char *name, const char *yaml)
{
    struct err e;
    struct compare *c = compare_load(job_file(name, yaml), &e);
    CHECK(c != NULL);
    if (c)
        c->scenes[0].ref_kind = COMPARE_REF_IMAGE;
    return c;
}

/* report_stability's line for (scene s, variant v) copied into buf, for strstr: the verdict of
   c's figures (and images in fx.dir) printed; ref NULL: as if the job had no reference. */
static void stability(struct compare *c, int s, int v, const struct rgbf *ref, char *buf, size_t n)
{
    struct err e;
    int kind = c->scenes[s].ref_kind;
    if (!ref)
        c->scenes[s].ref_kind = COMPARE_REF_NONE;
    verdict_study_free(&c->verdict);
    c->has_verdict = verdict_from_compare(c, fx.dir, NULL, &c->verdict, &e) == 0;
    CHECK(c->has_verdict);
    char *text = report_stability(c, s, v);
    snprintf(buf, n, "%s", text ? text : "");
    free(text);
    c->scenes[s].ref_kind = kind;
}

/* Hand-made results: relMSE falls as 1/spp for "noise", flattens for "flat". */
static void test_stats(void)
{
    struct compare *c = hand_made("st.yaml", "scenes: [SCENE]\nwidth: 8\nseeds: [1, 2]\n"
                                             "sweep: { threshold: [20, 10, 5] }\nvariants:\n"
                                             "  - { label: noise }\n  - { label: flat }\n");
    if (!c)
        return;
    for (int v = 0; v < 2; v++)
        for (int p = 0; p < 3; p++)
            for (int k = 0; k < 2; k++) {
                struct study_result *it = &c->results.rows[compare_index(c, 0, v, p, k)];
                double spp = 25 << (2 * p); /* 25, 100, 400 */
                it->done = it->has_error = 1;
                it->spp_mean = spp;
                it->wall_s = spp / 1000;
                it->error.relmse = (v == 0 ? 1 / spp : p == 2 ? 0.0095 : 0.4 / spp + 0.005) * (k ? 1.1 : 0.9);
            }
    struct compare_agg a;
    compare_stats_aggregate(c, 0, 0, 1, &a);
    CHECK(a.n == 2 && a.spp == 100);
    CHECK_NEAR(a.rel, 0.01, 1e-12);
    int order[3];
    compare_stats_point_order(c, 0, 0, order);
    CHECK(order[0] == 0 && order[1] == 1 && order[2] == 2);
    char line[1024];
    struct rgbf ref = {0};
    stability(c, 0, 0, &ref, line, sizeof line);
    /* the geometric mean's 95% interval over 2 seeds (0.9x, 1.1x): exp(12.706 x ln(1.1 / 0.9) / 2) */
    CHECK(strstr(line, "relMSE over 2 seeds known within a factor 3.58 either way") != NULL);
    CHECK(strstr(line, "relMSE ~ spp^-1.00") != NULL);
    CHECK(strstr(line, "error keeps falling down to threshold 5") != NULL);
    stability(c, 0, 1, &ref, line, sizeof line);
    CHECK(strstr(line, "error stops falling at threshold 5") != NULL);
    stability(c, 0, 1, NULL, line, sizeof line);
    CHECK(strstr(line, "no reference") != NULL);
    char *svg = report_chart_svg(c);
    CHECK(svg && strstr(svg, "checker: error against CPU time") && strstr(svg, ">flat<"));
    free(svg);
    compare_free(c);
}

/* A sweep that leaves samples per pixel alone (light_threshold): no slope against samples and no
   claim that error falls; relMSE per point in the sweep's order instead, and that order kept
   even when the seeds' sample counts differ by a hair (a poisson pixel sampler). */
static void test_stats_flat_samples(void)
{
    struct compare *c = hand_made("lt.yaml", "scenes: [SCENE]\nwidth: 8\nseeds: [1, 2]\n"
                                             "sweep: { light_threshold: [50, 25, 10] }\nvariants:\n"
                                             "  - { label: lights }\n");
    if (!c)
        return;
    static const double rel[3] = {0.03, 0.02, 0.021}, spp[3] = {66.9, 67.2, 67.0};
    for (int p = 0; p < 3; p++)
        for (int k = 0; k < 2; k++) {
            struct study_result *it = &c->results.rows[compare_index(c, 0, 0, p, k)];
            it->done = it->has_error = 1;
            it->spp_mean = spp[p];
            it->wall_s = 0.01 * (p + 1);
            it->error.relmse = rel[p];
        }
    int order[3];
    compare_stats_point_order(c, 0, 0, order);
    CHECK(order[0] == 0 && order[1] == 1 && order[2] == 2);
    char line[1024];
    struct rgbf ref = {0};
    stability(c, 0, 0, &ref, line, sizeof line);
    CHECK(!strstr(line, "nan") && !strstr(line, "spp^") && !strstr(line, "keeps falling"));
    CHECK(strstr(line, "light_threshold 50: 0.03, light_threshold 25: 0.02, light_threshold 10: 0.021") !=
          NULL);
    compare_free(c);
}

/* One seed: no spread to show, so the chart draws no whiskers and says why. */
static void test_chart_one_seed(void)
{
    struct compare *c = hand_made("one.yaml", "scenes: [SCENE]\nwidth: 8\n"
                                              "sweep: { threshold: [20, 10] }\nvariants:\n"
                                              "  - { label: a }\n");
    if (!c)
        return;
    for (int p = 0; p < 2; p++) {
        struct study_result *it = &c->results.rows[compare_index(c, 0, 0, p, 0)];
        it->done = it->has_error = 1;
        it->spp_mean = 25 << (2 * p);
        it->wall_s = 0.01 * (p + 1);
        it->error.relmse = 0.1 / it->spp_mean;
    }
    char *svg = report_chart_svg(c);
    CHECK(svg && !strstr(svg, "<path d=\"M") && !strstr(svg, "whisker") && !strstr(svg, "1 seeds"));
    CHECK(svg && strstr(svg, "one seed: no spread across seeds"));
    free(svg);
    compare_free(c);
}

/* The error that repeats in every seed, at every sweep point: images on disk where "same" is
   off the reference by +10 in both seeds (all of it repeats: aliasing, a bias) and "cancel" by
   +10 in one seed and -10 in the other (none repeats: noise). */
static void test_repeated_error(void)
{
    struct err e;
    struct compare *c = hand_made("rep.yaml", "scenes: [SCENE]\nwidth: 4\nheight: 4\n"
                                              "seeds: [1, 2]\nsweep: { threshold: [20, 10] }\n"
                                              "variants:\n  - { label: same }\n"
                                              "  - { label: cancel }\n");
    if (!c)
        return;
    /* in linear radiance, as a compare job measures: the seeds' float copies (<stem>.exr) */
    struct rgbf ref = {0}, img = {0};
    CHECK(image_f_alloc(&ref, 4, 4, &e) == 0 && image_f_alloc(&img, 4, 4, &e) == 0);
    for (int i = 0; i < 4 * 4 * 3; i++)
        ref.px[i] = 0.4f;
    snprintf(c->results.refs[0].path, sizeof c->results.refs[0].path, "%s/ref.exr", fx.dir);
    CHECK(imgio_write_f(c->results.refs[0].path, &ref, IMG_EXR, NULL, 0, &e) == 0);
    for (int v = 0; v < 2; v++)
        for (int p = 0; p < 2; p++)
            for (int k = 0; k < 2; k++) {
                const struct compare_item *it = &c->items[compare_index(c, 0, v, p, k)];
                struct study_result *r = &c->results.rows[compare_index(c, 0, v, p, k)];
                char path[1024];
                for (int i = 0; i < 4 * 4 * 3; i++)
                    img.px[i] = v == 0 || k == 0 ? 0.44f : 0.36f;
                snprintf(path, sizeof path, "%s/%.*s.exr", fx.dir, (int)strlen(it->job.output) - 4,
                         it->job.output);
                CHECK(imgio_write_f(path, &img, IMG_EXR, NULL, 0, &e) == 0);
                r->done = r->has_error = 1;
                r->spp_mean = 25 << (2 * p);
                r->wall_s = 0.01 * (p + 1);
                CHECK(metrics_compare_f(&ref, &img, 1, &r->error, &e) == 0);
            }
    char line[2048];
    stability(c, 0, 0, &ref, line, sizeof line);
    CHECK(strstr(line, "repeats in every seed: 100% at threshold 20 (bias 100%, pattern 0%), 100% at "
                       "threshold 10 (bias 100%, pattern 0%)") != NULL);
    stability(c, 0, 1, &ref, line, sizeof line);
    CHECK(strstr(line, "repeats in every seed: 0% at threshold 20, 0% at threshold 10") != NULL);
    image_f_free(&ref);
    image_f_free(&img);
    compare_free(c);
}

/* A scene's mask restricts the seed images' figures (mean radiance, the mean image's relMSE and its
   bias part) to its pixels: the right half, far off, does not count. */
static void test_masked_seed_images(void)
{
    struct err e;
    struct compare *c = hand_made("mask.yaml", "scenes: [SCENE]\nwidth: 4\nheight: 4\nseeds: [1, 2]\n"
                                               "mask: { rect: [0, 0, 2, 4] }\nvariants:\n  - { label: a }\n");
    if (!c)
        return;
    CHECK(c->scenes[0].mask != NULL);
    c->scenes[0].ref_domain = IMG_LINEAR;
    struct rgbf ref = {0}, img = {0};
    CHECK(image_f_alloc(&ref, 4, 4, &e) == 0 && image_f_alloc(&img, 4, 4, &e) == 0);
    for (int i = 0; i < 4 * 4 * 3; i++)
        ref.px[i] = 0.4f, img.px[i] = (i / 3) % 4 < 2 ? 0.44f : 1.2f;
    for (int k = 0; k < 2; k++) {
        const struct compare_item *it = &c->items[compare_index(c, 0, 0, 0, k)];
        char path[1024];
        snprintf(path, sizeof path, "%s/%.*s.exr", fx.dir, (int)strlen(it->job.output) - 4, it->job.output);
        CHECK(imgio_write_f(path, &img, IMG_EXR, NULL, 0, &e) == 0);
    }
    double radiance[2];
    struct compare_seed_stats st = {.radiance = radiance};
    CHECK(compare_stats_seed_images(c, 0, 0, 0, fx.dir, &ref, &st, &e) == 0);
    CHECK_NEAR(radiance[0], 0.44, 1e-6);
    CHECK_NEAR(st.rel_of_mean, 0.04 * 0.04 / (0.16 + 0.01), 1e-6);
    CHECK_NEAR(st.bias_rel, st.rel_of_mean, 1e-6); /* the masked part is all offset */
    CHECK_NEAR(compare_stats_mean_radiance(&img, c->scenes[0].mask), 0.44, 1e-6);
    CHECK_NEAR(compare_stats_mean_radiance(&img, NULL), 0.82, 1e-6);
    image_f_free(&ref), image_f_free(&img);
    /* the reference's noise from its halves, over the mask, a pixel's channels together: grey halves
       0.4 +- 0.1 give the mean radiance a standard error of sqrt(P x 0.1^2) / P over the P = 8
       pixels (counting the 24 values apart gave it sqrt(3) smaller) */
    struct rgbf a = {0}, b = {0};
    CHECK(image_f_alloc(&a, 4, 4, &e) == 0 && image_f_alloc(&b, 4, 4, &e) == 0);
    for (int i = 0; i < 4 * 4 * 3; i++)
        a.px[i] = 0.5f, b.px[i] = 0.3f;
    char path[1100];
    struct study_ref_result *rr = &c->results.refs[0];
    snprintf(rr->path, sizeof rr->path, "%s/halves.exr", fx.dir);
    snprintf(path, sizeof path, "%s/halves-a.exr", fx.dir);
    CHECK(imgio_write_f(path, &a, IMG_EXR, NULL, 0, &e) == 0);
    snprintf(path, sizeof path, "%s/halves-b.exr", fx.dir);
    CHECK(imgio_write_f(path, &b, IMG_EXR, NULL, 0, &e) == 0);
    compare_ref_measure(&c->scenes[0], rr);
    CHECK_NEAR(rr->fig.radiance, 0.4, 1e-6);
    CHECK_NEAR(rr->fig.radiance_se, sqrt(8 * 0.01) / 8, 1e-6);
    CHECK_NEAR(rr->fig.relmse, 0.01 / (0.16 + 0.01), 1e-6);
    image_f_free(&a), image_f_free(&b);
    compare_free(c);
}

/* Preparing a settings reference and rendering an image write the results (the reference's file,
   pixels and time, the image's row) and leave the plan byte for byte as loaded. */
static void test_run_keeps_plan(void)
{
    struct err e;
    struct compare *c =
        compare_load(job_file("plan.yaml", "name: plan\nscenes: [SCENE]\nwidth: 4\n"
                                           "reference: { sampler: jitter, threshold: 50 }\n"
                                           "variants:\n  - { sampler: jitter, threshold: 50 }\n"),
                     &e);
    CHECK(c != NULL && c->n_items == 1 && c->scenes[0].ref_kind == COMPARE_REF_SETTINGS);
    if (!c)
        return;
    struct compare_scene scene = c->scenes[0];
    struct compare_item it = c->items[0];
    struct run_opts o = {.out_dir = fx.dir, .quiet = 1, .processes = 1};
    CHECK(compare_ref_prepare(c, 0, &c->results, &o, &e) == 0);
    const struct study_ref_result *rr = &c->results.refs[0];
    CHECK(rr->ref && strstr(rr->path, "/.cache/ref-checker-") && !rr->fig.reused && rr->fig.spp > 0);
    CHECK(compare_run_item(c, &c->results, 0, &o, &e) == 0); /* prepares it again: reused */
    CHECK(!memcmp(&scene, &c->scenes[0], sizeof scene) && !memcmp(&it, &c->items[0], sizeof it));
    CHECK(c->results.rows[0].done && c->results.rows[0].has_error && c->results.rows[0].hash != 0);
    compare_free(c);
}

int main(void)
{
    if (compare_fixture_open(&fx, "test_compare") < 0)
        return 1;
    test_expand();
    test_two_keys_no_sweep();
    test_errors();
    test_stats();
    test_stats_flat_samples();
    test_chart_one_seed();
    test_repeated_error();
    test_masked_seed_images();
    test_run_keeps_plan();
    CHECK(compare_fixture_close(&fx) == 0);
    return check_report("test_compare");
}
