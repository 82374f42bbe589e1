/* test_verdict: the verdict's rules on constructed figures: a clear winner, a tie within the
   seeds' spread, an inconclusive ranking, slopes, each failure mode, the guards, and the JSON. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "verdict_fixture.h"
#include "study/judge/verdict.h"
#include "study/present/verdict_out.h"
#include "study/judge/verdict_rank.h"

#define NV 4
#define NP 3
#define NS 4
_Static_assert(NV <= VF_MAX_V && NP <= VF_MAX_P && NS <= VF_MAX_S, "verdict_fixture.h too small");

/* Figures built by hand (verdict_fixture.h): relMSE = k[v] / spp^-slope[v] x the seed's factor,
   CPU = spp x cost[v]. */
static const double seed_factor[NS] = {0.95, 1.0, 1.0, 1.05}; /* a 10% min-max range */
/* their geometric mean: what a ranking's value is */
#define GM pow(0.95 * 1.05, 0.25)

/* The seeds' mean image's relMSE at (v, p) that makes `share` of the error repeat in every seed:
   share = (n rel_of_mean / mean_rel - 1) / (n - 1). */
static void set_share(struct verdict_fixture *x, int v, int p, double share)
{
    int n = x->f.n_seeds;
    double mr = 0;
    for (int k = 0; k < n; k++)
        mr += x->rel[verdict_at(&x->f, v, p, k)] / n;
    x->rel_of_mean[v * NP + p] = mr * (1 + share * (n - 1)) / n;
}

static void fake_init(struct verdict_fixture *x, int nv, int ns, const double *k, const double *slope,
                      const double *cost)
{
    static const char *const names[NV] = {"alpha", "beta", "gamma", "delta"};
    static const double spp[NP] = {100, 400, 1600};
    verdict_fixture_init(x, "study", nv, NP, ns, 10000);
    x->points[0] = "threshold 10", x->points[1] = "threshold 5", x->points[2] = "threshold 2.5";
    for (int v = 0; v < nv; v++) {
        x->variants[v] = names[v];
        x->samplers[v] = "jitter";
        for (int p = 0; p < NP; p++) {
            x->bias_rel[v * NP + p] = 0;
            for (int s = 0; s < ns; s++) {
                int i = verdict_at(&x->f, v, p, s);
                x->spp[i] = spp[p];
                x->cpu[i] = spp[p] * cost[v];
                /* each variant's seeds in an order of its own: different samplers' seeds are
                   independent, so pairing by seed finds no shared factor */
                x->rel[i] = k[v] * pow(spp[p], slope[v]) * (ns > 1 ? seed_factor[(s + v) % NS] : 1);
                x->radiance[i] = 1;
            }
        }
    }
    for (int v = 0; v < nv; v++)
        for (int p = 0; p < NP; p++)
            set_share(x, v, p, 0.1);
}

/* hi / lo of the 95% interval of seed_factor's geometric mean: exp(2 x t(3 df) x se of the logs). */
static double ci_ratio(void)
{
    double m = 0, ss = 0;
    for (int k = 0; k < NS; k++)
        m += log(seed_factor[k]) / NS;
    for (int k = 0; k < NS; k++)
        ss += pow(log(seed_factor[k]) - m, 2);
    return exp(2 * 3.182446305 * sqrt(ss / (NS - 1) / NS));
}

static int rank_of(const struct verdict_ranking *r, int v)
{
    for (int i = 0; i < r->n; i++)
        if (r->e[i].variant == v)
            return r->e[i].rank;
    return -1;
}

static int has_failure(const struct verdict_scene *s, enum verdict_failure_kind kind, int v)
{
    for (int i = 0; i < s->n_failures; i++)
        if (s->failures[i].kind == kind && s->failures[i].variant == v)
            return 1;
    return 0;
}

static int any_line(char (*lines)[VERDICT_TEXT_MAX], int n, const char *needle)
{
    for (int i = 0; i < n; i++)
        if (strstr(lines[i], needle))
            return 1;
    return 0;
}

/* The rule on entries built from seeds: a gap far beyond the seeds' spread separates, one within
   it does not, on logarithms for relMSE; reaching the common point comes first. */
static void test_rule(void)
{
    struct verdict_entry e[2];
    const double a[3] = {0.9, 1.0, 1.1}, b[3] = {1.9, 2.0, 2.1}, c[3] = {0.5, 1.5, 3};
    verdict_entry_start(&e[0], 0), verdict_entry_start(&e[1], 1);
    for (int k = 0; k < 3; k++)
        verdict_entry_add(&e[0], a[k], 1), verdict_entry_add(&e[1], b[k], 1);
    verdict_entry_add(&e[0], -1, 1); /* not a relMSE: left out */
    verdict_entry_end(&e[0], 1), verdict_entry_end(&e[1], 1);
    /* lo, hi: the 95% interval, exp(mean log +- t(2 df) x its standard error) */
    double m = (log(0.9) + log(1.1)) / 3,
           sd = sqrt((pow(log(0.9) - m, 2) + m * m + pow(log(1.1) - m, 2)) / 2);
    CHECK(e[0].n == 3);
    CHECK_NEAR(e[0].lo, exp(m - 4.302652730 * sd / sqrt(3)), 1e-8);
    CHECK_NEAR(e[0].hi, exp(m + 4.302652730 * sd / sqrt(3)), 1e-8);
    CHECK_NEAR(e[0].value, exp((log(0.9) + log(1.1)) / 3), 1e-12); /* the geometric mean */
    struct verdict_ranking r = {.n = 2, .e = e};
    verdict_rank(&r);
    CHECK(r.status == VERDICT_CLEAR && e[0].variant == 0 && verdict_beats(&r, &e[0], &e[1]));
    CHECK(!verdict_beats(&r, &e[1], &e[0])); /* higher is worse */
    verdict_entry_start(&e[1], 1);
    for (int k = 0; k < 3; k++)
        verdict_entry_add(&e[1], c[k], 1); /* a wide spread around a close mean */
    verdict_entry_end(&e[1], 1);
    verdict_rank(&r);
    CHECK(r.status == VERDICT_INCONCLUSIVE && !verdict_beats(&r, &e[0], &e[1]));
    e[0].unreached = 1; /* better figures, but not at the common point */
    verdict_rank(&r);
    CHECK(e[0].variant == 1 && e[1].variant == 0 && e[1].rank == 2);
}

/* Separation is not transitive: a wide spread at a worse mean is beaten by none, while a narrow
   one between them is beaten; the ranking stays best first by rank (found in e2e_studies' tiny
   runs with the rule before). */
static void test_rank_order(void)
{
    struct verdict_entry e[3] = {{.variant = 0, .n = 8, .mean = 0.0, .se = 0.01},
                                 {.variant = 1, .n = 8, .mean = 0.2, .se = 0.5},
                                 {.variant = 2, .n = 8, .mean = 0.1, .se = 0.01}};
    struct verdict_ranking r = {.n = 3, .e = e};
    verdict_rank(&r);
    CHECK(e[0].variant == 0 && e[0].rank == 1);
    CHECK(e[1].variant == 1 && e[1].rank == 1); /* nobody tells the wide spread apart */
    CHECK(e[2].variant == 2 && e[2].rank == 2); /* variant 0 beats it */
    CHECK(r.status == VERDICT_TIE);
}

static void test_clear_winner(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    const double k[] = {1, 2, 4}, slope[] = {-1, -1, -1}, cost[] = {1e-3, 1e-3, 4e-3};
    fake_init(&x, 3, NS, k, slope, cost);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_samples.status == VERDICT_CLEAR);
    CHECK_NEAR(s.by_samples.at, 1600, 1e-9);
    CHECK(s.by_samples.e[0].variant == 0 && rank_of(&s.by_samples, 0) == 1);
    CHECK(rank_of(&s.by_samples, 1) == 2 && rank_of(&s.by_samples, 2) == 3);
    CHECK_NEAR(s.by_samples.e[0].value, GM * 1.0 / 1600, 1e-12);
    CHECK_NEAR(s.by_samples.e[0].hi / s.by_samples.e[0].lo, ci_ratio(), 1e-9);
    /* equal CPU time: the cheapest densest point, 1.6 s; gamma (4x the cost per sample) is read at
       its 400-spp point there */
    CHECK(s.by_cpu.status == VERDICT_CLEAR);
    CHECK_NEAR(s.by_cpu.at, 1.6, 1e-9);
    CHECK_NEAR(s.by_cpu.e[2].value, GM * 4.0 / 400, 1e-9);
    CHECK(s.by_slope.status == VERDICT_INCONCLUSIVE); /* every slope is -1 */
    CHECK_NEAR(s.by_slope.e[0].value, -1, 1e-9);
    CHECK(s.n_failures == 0);
    /* these figures have no cost design: the images' own times, said so */
    CHECK(s.n_warnings == 2 && strstr(s.warnings[0], "no cost design measured") &&
          strstr(s.warnings[1], "by slope, ") &&
          strstr(s.warnings[1],
                 "are not told apart by their seeds (Welch's t test, Holm-corrected, alpha 0.05)"));
    CHECK(any_line(s.sentences, s.n_sentences, "use alpha"));
    char w[64];
    verdict_ranking_winner(&s, &s.by_cpu, 1, w, sizeof w);
    CHECK(!strcmp(w, "alpha"));
    verdict_scene_free(&s);
}

static void test_tie_and_inconclusive(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    const double k[] = {1, 1.05, 4}, slope[] = {-1, -1, -1}, cost[] = {1e-3, 1e-3, 1e-3};
    fake_init(&x, 3, NS, k, slope, cost);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_samples.status == VERDICT_TIE); /* alpha and beta 5% apart, each with a 10% range */
    CHECK(rank_of(&s.by_samples, 0) == 1 && rank_of(&s.by_samples, 1) == 1 && rank_of(&s.by_samples, 2) == 3);
    CHECK(any_line(s.sentences, s.n_sentences, "alpha, beta tie"));
    CHECK(any_line(s.warnings, s.n_warnings,
                   "at equal samples, alpha, beta are not told apart by their seeds "
                   "(Welch's t test, Holm-corrected, alpha 0.05): tied, no single winner"));
    char w[64];
    verdict_ranking_winner(&s, &s.by_cpu, 1, w, sizeof w);
    CHECK(!strcmp(w, "alpha = beta (tie)"));
    verdict_scene_free(&s);

    fake_init(&x, 2, NS, k, slope, cost); /* only the two close ones: nobody is ahead */
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_samples.status == VERDICT_INCONCLUSIVE && s.by_cpu.status == VERDICT_INCONCLUSIVE);
    CHECK(any_line(s.sentences, s.n_sentences, "inconclusive"));
    verdict_ranking_winner(&s, &s.by_cpu, 1, w, sizeof w);
    CHECK(!strcmp(w, "inconclusive"));
    verdict_scene_free(&s);

    const double far[] = {1, 4, 4};
    fake_init(&x, 3, 1, far, slope, cost); /* one seed: no spread, so no ranking */
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_samples.status == VERDICT_INCONCLUSIVE);
    CHECK(any_line(s.warnings, s.n_warnings, "one seed"));
    verdict_scene_free(&s);

    fake_init(&x, 3, NS, far, slope, cost); /* no reference: no error anywhere, so nothing to rank by */
    for (int i = 0; i < 3 * NP * NS; i++)
        x.rel[i] = NAN;
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_samples.status == VERDICT_INCONCLUSIVE && s.by_cpu.status == VERDICT_INCONCLUSIVE);
    CHECK(any_line(s.warnings, s.n_warnings, "no reference: no image has an error to rank by"));
    CHECK(any_line(s.sentences, s.n_sentences, "inconclusive (no reference: no error to compare)."));
    CHECK(!any_line(s.sentences, s.n_sentences, "more seeds or samples would tell"));
    verdict_scene_free(&s);
}

static void test_slopes(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    const double k[] = {1, 1, 1}, slope[] = {-1, -1.3, -1.02}, cost[] = {1e-3, 1e-3, 1e-3};
    fake_init(&x, 3, NS, k, slope, cost);
    for (int p = 0; p < NP; p++) /* per-seed slopes that differ a little: seed 2 steeper */
        x.rel[verdict_at(&x.f, 1, p, 2)] *= pow(1.0 + p, -0.05);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_slope.status == VERDICT_CLEAR && s.by_slope.e[0].variant == 1);
    CHECK(s.by_slope.e[0].lo < s.by_slope.e[0].hi); /* the spread across seeds */
    /* alpha's and gamma's seeds agree exactly (no spread), so even -1.02 against -1 counts */
    CHECK(rank_of(&s.by_slope, 2) == 2 && rank_of(&s.by_slope, 0) == 3);
    CHECK(any_line(s.sentences, s.n_sentences, "Error falls fastest with beta"));
    verdict_scene_free(&s);
}

static void test_failures_and_guards(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    const double k[] = {1, 1.5, 3, 2}, slope[] = {-1, -1, -1, -1}, cost[] = {1e-3, 1e-3, 3e-3, 1e-3};
    fake_init(&x, 4, NS, k, slope, cost);
    x.samplers[1] = "uniform";
    set_share(&x, 1, 0, 0.9); /* uniform: most of its error repeats at the sparsest point */
    x.samplers[2] = "poisson";
    for (int p = 0; p < NP; p++)
        for (int k2 = 0; k2 < NS; k2++) {
            x.share[verdict_at(&x.f, 2, p, k2)] = 0.7; /* Bridson's sets dominate */
            x.rel[verdict_at(&x.f, 3, p, k2)] = 0.002 * (p ? 0.95 : 1) * seed_factor[k2]; /* stalls */
        }
    x.nonfinite[verdict_at(&x.f, 3, 1, 0)] = 3;
    x.f.ref.spp = 3000; /* under 4x the densest point's 1600 */
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(has_failure(&s, VERDICT_STRUCTURED, 1) && !has_failure(&s, VERDICT_STRUCTURED, 0));
    CHECK(has_failure(&s, VERDICT_SHARE, 2) && !has_failure(&s, VERDICT_SHARE, 0));
    CHECK(has_failure(&s, VERDICT_STALLS, 3) && !has_failure(&s, VERDICT_STALLS, 0));
    CHECK(has_failure(&s, VERDICT_NONFINITE, 3) && !has_failure(&s, VERDICT_NONFINITE, 1));
    CHECK(any_line(s.sentences, s.n_sentences, "beta aliases on board: 90% of its error at threshold 10"));
    CHECK(any_line(s.sentences, s.n_sentences,
                   "gamma costs 3.0x alpha's CPU time per sample and buys nothing"));
    CHECK(any_line(s.warnings, s.n_warnings, "the reference has 3000 samples per pixel"));
    char *json = verdict_json_text("job", &(struct verdict_study){"study", 1, &s, ""}, 1, NULL);
    CHECK(json && strstr(json, "\"kind\": \"structured_error\"") &&
          strstr(json, "\"kind\": \"sampler_share\"") && strstr(json, "\"equal_cpu_time\"") &&
          strstr(json, "\"tie_rule\""));
    free(json);
    verdict_scene_free(&s);
    x.f.ref.spp = 6400; /* exactly 4x: no warning */
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(!any_line(s.warnings, s.n_warnings, "the reference has"));
    verdict_scene_free(&s);
}

/* A variant whose cheapest image costs more than the others' densest is read at the common time
   along its own error-against-time line (extrapolated), never ranked behind for costing more: worse
   there it ranks behind, better it ranks first (issue 35's furnace), too far beyond its points the
   study cannot tell. */
static void test_unreached(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    double k[] = {1, 2, 0.5}, slope[] = {-1, -1, -1}, cost[] = {1e-3, 1e-3, 50e-3};
    fake_init(&x, 3, NS, k, slope, cost);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_samples.e[0].variant == 2 && s.by_samples.status == VERDICT_CLEAR); /* best per sample */
    /* at 1.6 s gamma would draw 32 samples: relMSE 0.5 / 32, far above alpha's 1 / 1600 */
    CHECK(s.by_cpu.e[2].variant == 2 && s.by_cpu.e[2].extrapolated && !s.by_cpu.e[2].untold);
    CHECK(!s.by_cpu.e[2].unreached && s.by_cpu.e[2].rank == 3);
    CHECK_NEAR(s.by_cpu.e[2].value, GM * 0.5 / 32, 1e-9);
    CHECK(any_line(s.warnings, s.n_warnings,
                   "gamma is read at 1.6 CPU seconds along its error-against-time line"));
    verdict_scene_free(&s);

    k[2] = 0.001; /* 500x better per sample at 50x the cost: 0.001 / 32 at equal time beats 1 / 1600 */
    fake_init(&x, 3, NS, k, slope, cost);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_cpu.status == VERDICT_CLEAR && s.by_cpu.e[0].variant == 2 && s.by_cpu.e[0].rank == 1);
    verdict_scene_free(&s);

    cost[2] = 500e-3; /* its cheapest at 50 s: 31x beyond 1.6 s, farther than its points span (16x) */
    fake_init(&x, 3, NS, k, slope, cost);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_cpu.e[0].untold || s.by_cpu.e[1].untold || s.by_cpu.e[2].untold);
    CHECK(rank_of(&s.by_cpu, 2) == 1); /* separated from none: not behind */
    CHECK(any_line(s.warnings, s.n_warnings, "the study cannot tell where gamma stands"));
    verdict_scene_free(&s);
}

/* A synthetic study where beta's seeds' mean radiance sits 2% above the reference's (a biased
   sampler, like the seed's square-domain Poisson sets): flagged `biased` with the percentage;
   alpha, off by a fraction of a standard error, is not; and the repeated share splits into bias
   and pattern. */
static void test_biased(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    const double k[] = {1, 0.5, 1}, slope[] = {-1, -1, -1}, cost[] = {1e-3, 1e-3, 1e-3};
    static const double noise[NS] = {-0.004, 0.001, 0.002, 0.001};
    fake_init(&x, 3, NS, k, slope, cost);
    for (int p = 0; p < NP; p++)
        for (int k2 = 0; k2 < NS; k2++) {
            x.radiance[verdict_at(&x.f, 0, p, k2)] = 1.0 + noise[k2];
            x.radiance[verdict_at(&x.f, 1, p, k2)] = 1.02 + noise[k2];
            x.radiance[verdict_at(&x.f, 2, p, k2)] =
                1.0 + 4 * noise[k2] + (p == 2 ? 0.004 : 0); /* within 4 SE */
        }
    x.f.ref.radiance = 1.0, x.f.ref.radiance_se = 0.001;
    set_share(&x, 1, 2, 0.8);
    x.bias_rel[1 * NP + 2] = 0.6 * x.rel[verdict_at(&x.f, 1, 2, 1)]; /* 0.6 of the mean relMSE */
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(has_failure(&s, VERDICT_BIASED, 1) && !has_failure(&s, VERDICT_BIASED, 0) &&
          !has_failure(&s, VERDICT_BIASED, 2));
    for (int i = 0; i < s.n_failures; i++)
        if (s.failures[i].kind == VERDICT_BIASED) {
            CHECK_NEAR(s.failures[i].value, 2.0, 1e-9); /* percent */
            CHECK(s.failures[i].detail > 4);
            CHECK(strstr(s.failures[i].text,
                         "beta: biased: its seeds' mean radiance at threshold 10 is +2.00% off"));
        }
    CHECK(any_line(s.sentences, s.n_sentences, "beta is biased on board"));
    /* beta's error is the lowest now: the sentence that names it says it is biased */
    CHECK(any_line(s.sentences, s.n_sentences, "use beta: relMSE"));
    CHECK(any_line(
        s.sentences, s.n_sentences,
        "But beta is biased (+2.00% in mean radiance): more samples will not bring it to the reference."));
    CHECK_NEAR(s.repeat[1 * NP + 2], 0.8, 1e-9);
    CHECK(s.repeat_bias[1 * NP + 2] > 0.59 && s.repeat_bias[1 * NP + 2] < 0.61);
    for (int i = 0; i < s.n_failures; i++)
        if (s.failures[i].kind == VERDICT_STRUCTURED)
            CHECK(strstr(s.failures[i].text,
                         "80% of its error at threshold 2.5 repeats in every seed (60% a bias"));
    char *json = verdict_json_text("job", &(struct verdict_study){"study", 1, &s, ""}, 1, NULL);
    CHECK(json && strstr(json, "\"kind\": \"biased\"") && strstr(json, "\"bias_share\""));
    free(json);
    verdict_scene_free(&s);
}

/* The reference's own relMSE is subtracted before ranking and fitting, and a point within 2x of it
   is warned: alpha's relMSE k / spp plus a reference floor of 1e-3 fits its true slope -1. */
static void test_reference_noise(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    const double k[] = {1, 2}, slope[] = {-1, -1}, cost[] = {1e-3, 1e-3};
    fake_init(&x, 2, NS, k, slope, cost);
    for (int i = 0; i < 2 * NP * NS; i++)
        x.rel[i] += 1e-3;
    x.f.ref.relmse = 1e-3;
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK_NEAR(s.by_slope.e[0].value, -1, 1e-9);
    CHECK_NEAR(s.by_samples.e[0].value, GM / 1600, 1e-12);
    CHECK_NEAR(s.ref_relmse, 1e-3, 1e-15);
    CHECK(any_line(s.warnings, s.n_warnings,
                   "alpha's relMSE is within 2x of the reference's own 0.001 at threshold 2.5"));
    CHECK(!any_line(s.warnings, s.n_warnings, "at threshold 5 ("));
    char *json = verdict_json_text("job", &(struct verdict_study){"study", 1, &s, ""}, 1, NULL);
    CHECK(json && strstr(json, "\"reference_relmse\": 0.001"));
    free(json);
    verdict_scene_free(&s);
    x.f.ref.relmse = NAN; /* unknown: the floor stays in, the slope flattens */
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.by_slope.e[0].value > -0.9);
    verdict_scene_free(&s);
}

int main(void)
{
    test_biased();
    test_reference_noise();
    test_unreached();
    test_rule();
    test_rank_order();
    test_clear_winner();
    test_tie_and_inconclusive();
    test_slopes();
    test_failures_and_guards();
    return check_report("test_verdict");
}
