/* test_verdict_fireflies: the heavy_tailed failure mode on constructed figures shaped like issue
   38's furnace (tests/data/furnace-fireflies.yaml): the mixture, whose variance is infinite, is
   flagged heavy_tailed and not biased or stalling; nee and a light-tailed spread of 2x are not. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "verdict_fixture.h"
#include "study/judge/verdict.h"
#include "study/judge/verdict_center.h"
#include "study/present/verdict_out.h"

#define NP 3
#define NS 8

/* Per-seed relMSE of the furnace study at thresholds 25 and 12.5 (summary.csv of a 24x24 run, seeds
   1-8), and a third point at 4x the samples where the firefly seed moved. */
static const double mixture[NP][NS] = {{0.00974, 0.540, 0.0538, 0.0110, 0.0449, 0.0626, 0.00747, 0.138},
                                       {0.0108, 3.68, 0.00555, 0.00277, 0.00817, 0.00591, 0.00465, 0.0367},
                                       {0.00301, 0.00291, 0.00108, 0.00262, 0.0012, 4.1, 0.0019, 0.0022}};
/* Seeds 9-16 of the same study: fireflies in several seeds. */
static const double mixture2[NP][NS] = {{0.0619, 0.0086, 0.00759, 0.0178, 0.00748, 0.137, 0.00712, 0.0635},
                                        {0.0118, 0.00548, 0.028, 0.0236, 0.00648, 0.0116, 0.00333, 0.00626},
                                        {0.0118, 0.00548, 0.028, 0.0236, 0.00648, 0.0116, 0.00333, 0.00626}};
/* Another run: no seed drew a firefly at threshold 25 (all tight and low, so the mean radiance is
   low: the old verdict called it biased), half of them did at 12.5. */
static const double bimodal[NP][NS] = {
    {0.00899, 0.00813, 0.00594, 0.00915, 0.00925, 0.0053, 0.00662, 0.00735},
    {0.00459, 0.0379, 0.00465, 0.0047, 0.00435, 0.0305, 0.0683, 0.0452},
    {0.00459, 0.0379, 0.00465, 0.0047, 0.00435, 0.0305, 0.0683, 0.0452}};
static const double nee[NP][NS] = {
    {0.00110, 0.00121, 0.00107, 0.00141, 0.00118, 0.00154, 0.00112, 0.00147},
    {0.000257, 0.000339, 0.000337, 0.000404, 0.000270, 0.000439, 0.000367, 0.000381},
    {0.0000642, 0.0000847, 0.0000843, 0.000101, 0.0000675, 0.000110, 0.0000918, 0.0000952}};

static int has(const struct verdict_scene *s, enum verdict_failure_kind k, int v)
{
    for (int i = 0; i < s->n_failures; i++)
        if (s->failures[i].kind == k && s->failures[i].variant == v)
            return 1;
    return 0;
}

static void fill(struct verdict_fixture *x, const double (*fig)[NS])
{
    static const double spp[NP] = {16, 64, 256};
    verdict_fixture_init(x, "furnace", 3, NP, NS, 4096);
    x->points[0] = "threshold 25", x->points[1] = "threshold 12.5", x->points[2] = "threshold 6.25";
    const char *names[3] = {"mixture", "nee", "spread"};
    for (int v = 0; v < 3; v++) {
        x->variants[v] = names[v], x->samplers[v] = "jitter";
        for (int p = 0; p < NP; p++)
            for (int k = 0; k < NS; k++) {
                int i = verdict_at(&x->f, v, p, k);
                x->spp[i] = spp[p], x->cpu[i] = spp[p] * 1e-5;
                /* the mixture's typical seeds miss the rare large samples: 14% dark, tightly */
                x->rel[i] = v == 0 ? fig[p][k] : v == 1 ? nee[p][k] : nee[p][k] * (k == 3 ? 2 : 1);
                x->radiance[i] = v == 0 ? 0.86 + 0.002 * (k % 3) : 1 + 0.002 * ((k % 3) - 1);
            }
        for (int p = 0; p < NP; p++)
            x->rel_of_mean[v * NP + p] = NAN, x->bias_rel[v * NP + p] = NAN;
    }
    x->f.ref.radiance = 1, x->f.ref.radiance_se = 0.001;
}

static void test_furnace(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    fill(&x, mixture);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(has(&s, VERDICT_HEAVY_TAILED, 0));
    CHECK(!has(&s, VERDICT_BIASED, 0) && !has(&s, VERDICT_STALLS, 0));
    CHECK(!has(&s, VERDICT_HEAVY_TAILED, 1) && !has(&s, VERDICT_BIASED, 1));
    CHECK(!has(&s, VERDICT_HEAVY_TAILED, 2)); /* one seed at 2x its fellows */
    for (int i = 0; i < s.n_failures; i++)
        if (s.failures[i].kind == VERDICT_HEAVY_TAILED) {
            CHECK(s.failures[i].point == 2);
            CHECK_NEAR(s.failures[i].value, 4.1 / 0.00108, 1e-6 * 4.1 / 0.00108);
            CHECK(strstr(s.failures[i].text,
                         "mixture: fireflies: its seeds' relMSE at threshold 6.25 span a factor 3.8e+03"));
        }
    CHECK(strstr(s.sentences[s.n_sentences - 1], "mixture has fireflies on board") ||
          strstr(s.sentences[s.n_sentences - 2], "mixture has fireflies on board"));
    char *json = verdict_json_text("job", &(struct verdict_study){"furnace", 1, &s, ""}, 1, NULL);
    CHECK(json && strstr(json, "\"kind\": \"heavy_tailed\"") && strstr(json, "\"worst_share\""));
    free(json);
    verdict_scene_free(&s);
}

/* Without its fireflies (every seed like the typical ones) the same mixture is biased: the mean of
   the seeds that missed the rare samples is what the bias test reads, which is why fireflies
   suppress it. */
static void test_suppresses(void)
{
    static double tame[NP][NS];
    for (int p = 0; p < NP; p++)
        for (int k = 0; k < NS; k++)
            tame[p][k] = nee[p][k] * 10;
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    fill(&x, (const double(*)[NS])tame);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(!has(&s, VERDICT_HEAVY_TAILED, 0) && has(&s, VERDICT_BIASED, 0));
    verdict_scene_free(&s);
    fill(&x, mixture2); /* 0.137 against 0.00712 */
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(has(&s, VERDICT_HEAVY_TAILED, 0) && !has(&s, VERDICT_BIASED, 0));
    verdict_scene_free(&s);
    fill(&x, bimodal); /* 0.0683 against 0.00435 */
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(has(&s, VERDICT_HEAVY_TAILED, 0) && !has(&s, VERDICT_BIASED, 0) && !has(&s, VERDICT_STALLS, 0));
    verdict_scene_free(&s);
    /* fewer than 4 seeds: no claim (with 2 the worst always carries half) */
    fill(&x, mixture);
    x.f.n_seeds = 3;
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(!has(&s, VERDICT_HEAVY_TAILED, 0));
    verdict_scene_free(&s);
}

/* rank_by: median: a variant whose seeds are alike but for one firefly seed (1000x) against one
   twice as bad on every seed: the geometric mean cannot tell them apart (the firefly's log widens
   the spread), the median ranks the first ahead; and the median's standard error from the order
   statistics on known numbers. */
static void test_rank_by_median(void)
{
    static const double base[NS] = {1.0, 1.1, 0.9, 1.05, 0.95, 1.02, 0.98, 1.0};
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    verdict_fixture_init(&x, "median", 2, 1, NS, 4096);
    x.variants[0] = "firefly", x.variants[1] = "steady", x.samplers[0] = x.samplers[1] = "jitter";
    x.points[0] = "threshold 10";
    for (int v = 0; v < 2; v++) {
        x.rel_of_mean[v] = x.bias_rel[v] = NAN;
        for (int k = 0; k < NS; k++) {
            int i = verdict_at(&x.f, v, 0, k);
            x.spp[i] = 16, x.cpu[i] = 1e-3, x.radiance[i] = NAN;
            x.rel[i] = 1e-3 * base[k] * (v ? 2 : k == 5 ? 1000 : 1);
        }
    }
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_samples.status == VERDICT_INCONCLUSIVE);
    verdict_scene_free(&s);
    x.f.rank_by = VERDICT_RANK_MEDIAN;
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_samples.status == VERDICT_CLEAR && s.by_samples.e[0].variant == 0);
    CHECK_NEAR(s.by_samples.e[0].value, 1e-3, 1e-12); /* base sorted with the firefly: 1.0, 1.0 mid */
    CHECK_NEAR(s.point_rel[0], 1e-3, 1e-12);          /* the chart's and table's figure too */
    char *json = verdict_json_text("job", &(struct verdict_study){"median", 1, &s, ""}, 1, NULL);
    CHECK(json && strstr(json, "\"rank_by\": \"median\""));
    free(json);
    verdict_scene_free(&s);
    /* 8 values 1..8: median 4.5; c = round(4.5 - 1.96 x sqrt 2) = 2: se = (x7 - x2) / 3.92 */
    const double v8[8] = {8, 1, 7, 2, 6, 3, 5, 4};
    double c, var;
    CHECK(verdict_center(v8, 8, VERDICT_RANK_MEDIAN, &c, &var) == 8);
    CHECK_NEAR(c, 4.5, 1e-12);
    CHECK_NEAR(sqrt(var), 5 / (2 * 1.959964), 1e-9);
    CHECK(verdict_center(v8, 8, VERDICT_RANK_MEAN, &c, &var) == 8 && fabs(c - 4.5) < 1e-12);
    CHECK_NEAR(var, 6.0 / 8, 1e-12); /* s^2 = 6 (sum of squares 42 / 7) */
}

int main(void)
{
    test_rank_by_median();
    test_furnace();
    test_suppresses();
    return check_report("test_verdict_fireflies");
}
