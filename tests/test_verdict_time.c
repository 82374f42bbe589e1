/* test_verdict_time: equal CPU time with both uncertainties, on constructed figures: identical
   variants whose images' own times a load stretch tilted stay tied when the cost design's blocks
   say they cost alike; a load that moves whole blocks cancels in the pairs; an error gap within
   the cost's uncertainty is not a separation, beyond it it is; and the per-point figures (the
   geometric mean with its 95% interval) every presentation uses. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "verdict_fixture.h"
#include "study/judge/verdict.h"
#include "study/judge/verdict_rank.h"

#define NV 4
#define NP 2
#define NS 8
#define NB 10

static const double spp[NP] = {16, 64};

/* x: NV variants of identical images (relMSE 1/spp times a seed factor shared by all: byte-identical
   images), each image's own CPU time tilted by `tilt[v]` (a stretch of load), and a cost design whose
   block b costs everyone `block_load[b]` times the true cost, times a small own noise. */
static void aa_init(struct verdict_fixture *x, double *cost, const double *tilt, const double *block_load,
                    double own_noise)
{
    static const char *const names[NV] = {"a", "b", "c", "d"};
    verdict_fixture_init(x, "aa", NV, NP, NS, 10000);
    x->points[0] = "threshold 25", x->points[1] = "threshold 12.5";
    for (int v = 0; v < NV; v++) {
        x->variants[v] = names[v], x->samplers[v] = "random";
        for (int p = 0; p < NP; p++) {
            x->rel_of_mean[v * NP + p] = x->bias_rel[v * NP + p] = NAN;
            for (int k = 0; k < NS; k++) {
                int i = verdict_at(&x->f, v, p, k);
                x->spp[i] = spp[p];
                x->rel[i] = (1 + 0.3 * sin(k + 7 * p)) / spp[p]; /* the same in every variant */
                x->cpu[i] = spp[p] * 1e-4 * tilt[v];
                x->radiance[i] = NAN;
            }
            for (int b = 0; b < NB; b++) /* a deterministic noise of its own per (v, p, b) */
                cost[(v * NP + p) * NB + b] =
                    spp[p] * 1e-4 * block_load[b] * (1 + own_noise * sin(13.7 * v + 5.3 * p + 2.1 * b));
        }
    }
    x->f.n_blocks = NB, x->f.cost_s = cost;
}

/* No tilt, no load: every variant's images cost alike, every block alike. */
static const double even[NV] = {1, 1, 1, 1}, flat[NB] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1};

static void test_aa(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    double cost[NV * NP * NB];
    const double tilt[NV] = {1, 0.7, 1.3, 1}; /* the images' own times: b rendered in a quiet stretch */
    double drift[NB];
    for (int b = 0; b < NB; b++)
        drift[b] = b % 3 ? 1 : 2.5; /* a hog on every third block */
    aa_init(&x, cost, tilt, flat, 0.02);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_cpu.status == VERDICT_INCONCLUSIVE); /* the old rule, on the images' times: b ahead */
    CHECK(!s.cost_from_images);
    verdict_scene_free(&s);

    aa_init(&x, cost, tilt, drift, 0.02); /* load moving whole blocks: cancels in the pairs */
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_cpu.status == VERDICT_INCONCLUSIVE);
    verdict_scene_free(&s);
    int symmetric = 1; /* one p-value per pair, the same both ways bit for bit (Holm's cut is one) */
    for (int i = 1; i <= 20; i++) {
        aa_init(&x, cost, tilt, drift, 0.013 * i);
        for (int k = 0; k < NS; k++) /* the variants' errors apart: seeds of their own */
            for (int v = 0; v < NV; v++)
                x.rel[verdict_at(&x.f, v, 1, k)] *= 1 + 0.1 * sin(3.3 * k + v * i);
        CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
        for (int a = 0; a < NV; a++)
            for (int b = 0; b < NV; b++)
                symmetric &= s.by_cpu.pair_p[a * NV + b] == s.by_cpu.pair_p[b * NV + a];
        verdict_scene_free(&s);
    }
    CHECK(symmetric);
    aa_init(&x, cost, tilt, drift, 0.02);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    for (int v = 0; v < NV; v++) /* and widens nobody's interval past reason: the blocks' own spread */
        CHECK(s.by_cpu.e[v].hi > s.by_cpu.e[v].value && s.by_cpu.e[v].lo < s.by_cpu.e[v].value);
    verdict_scene_free(&s);

    x.f.cost_s = NULL; /* no cost design: the images' own times, tilted, separate (why the design
                          exists), and a warning says whose times they are */
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.cost_from_images && s.by_cpu.status != VERDICT_INCONCLUSIVE);
    int warned = 0;
    for (int i = 0; i < s.n_warnings; i++)
        warned |= strstr(s.warnings[i], "no cost design measured") != NULL;
    CHECK(warned);
    verdict_scene_free(&s);
}

/* Two variants whose error differs by 10% (seeds independent), at a cost known exactly: told
   apart; the same with a cost that is 25% uncertain per block: not. */
static void test_cost_uncertainty(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    double cost[NV * NP * NB];
    for (int noisy = 0; noisy < 2; noisy++) {
        aa_init(&x, cost, even, flat, noisy ? 0.25 : 0.001);
        x.f.n_variants = 2;
        for (int p = 0; p < NP; p++)
            for (int k = 0; k < NS; k++) {
                x.rel[verdict_at(&x.f, 0, p, k)] = (1 + 0.01 * sin(3.0 * k + p)) / spp[p];
                x.rel[verdict_at(&x.f, 1, p, k)] = 1.1 * (1 + 0.01 * cos(5.0 * k + p)) / spp[p];
            }
        CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
        /* one p-value per pair, the same both ways bit for bit: Holm's cut is one of them, and a
           pair whose other way came out an ulp above it would not be separated */
        for (int a = 0; a < 2; a++)
            for (int b = 0; b < 2; b++)
                CHECK(s.by_cpu.pair_p[a * s.by_cpu.pair_n + b] == s.by_cpu.pair_p[b * s.by_cpu.pair_n + a]);
        CHECK(noisy ? s.by_cpu.status == VERDICT_INCONCLUSIVE
                    : s.by_cpu.status == VERDICT_CLEAR && s.by_cpu.e[0].variant == 0);
        CHECK(s.by_samples.status == VERDICT_CLEAR); /* at equal samples the cost plays no part */
        verdict_scene_free(&s);
    }
}

/* The per-point figure: the geometric mean over seeds with its 95% interval (t with n - 1 df), the
   cost design's likewise; one seed: the value itself, and no "stops falling" from one seed. */
static void test_points(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    double cost[NV * NP * NB];
    aa_init(&x, cost, even, flat, 0.02);
    x.f.n_seeds = 2; /* the figures laid out again for two seeds */
    for (int v = 0; v < NV; v++)
        for (int p = 0; p < NP; p++)
            for (int k = 0; k < 2; k++) {
                int i = verdict_at(&x.f, v, p, k);
                x.spp[i] = spp[p], x.cpu[i] = spp[p] * 1e-4, x.rel[i] = k ? 4 : 1;
            }
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK_NEAR(s.point_rel[0], 2, 1e-12);
    /* logs 0 and ln 4: mean ln 2, standard error ln 2; t(1 df) 97.5% = 12.7062 */
    CHECK_NEAR(s.point_rel_lo[0], exp(log(2) - 12.70620474 * log(2)), 1e-9);
    CHECK_NEAR(s.point_rel_hi[0] / exp(log(2) + 12.70620474 * log(2)), 1, 1e-6);
    CHECK(s.cost[0] > 0);
    CHECK_NEAR(s.cost[1] / s.cost[0], 4, 0.1); /* 64 against 16 samples */
    verdict_scene_free(&s);

    x.f.n_seeds = 1; /* one seed, whose error rises along the sweep: no spread, no claim */
    for (int v = 0; v < NV; v++)
        for (int p = 0; p < NP; p++) {
            int i = verdict_at(&x.f, v, p, 0);
            x.spp[i] = spp[p], x.cpu[i] = spp[p] * 1e-4, x.rel[i] = p ? 0.02 : 0.01;
        }
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.point_rel_lo[0] == s.point_rel[0] && s.point_rel_hi[0] == s.point_rel[0]);
    for (int i = 0; i < s.n_failures; i++)
        CHECK(s.failures[i].kind != VERDICT_STALLS);
    verdict_scene_free(&s);
}

int main(void)
{
    CHECK_NEAR(verdict_t_975(1), 12.70620474, 1e-6);
    CHECK_NEAR(verdict_t_975(7), 2.364624252, 1e-6);
    CHECK_NEAR(verdict_t_p(2.364624252, 7), 0.05, 1e-6);
    test_aa();
    test_cost_uncertainty();
    test_points();
    return check_report("test_verdict_time");
}
