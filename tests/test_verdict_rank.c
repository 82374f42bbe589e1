/* test_verdict_rank: the separation rule's arithmetic (Welch's p-value, Holm's cut) and its error
   rates measured on thousands of synthetic studies: false separation among six identical variants
   and power at gaps of 1, 2 and 3 standard deviations, with 8 seeds (docs/compare.md quotes the
   figures printed here). */
#include <math.h>
#include <stdio.h>

#include "base/rng.h"
#include "check.h"
#include "study/judge/verdict_rank.h"

#define STUDIES 4000
#define SEEDS 8
#define MAXV 6

/* An entry of n seeds whose ranked figure has this mean and standard error (no seeds added). */
static struct verdict_entry entry(int n, double mean, double se)
{
    return (struct verdict_entry){.n = n, .mean = mean, .se = se};
}

static void test_welch_p(void)
{
    /* equal seeds and spread: Welch's degrees of freedom are 2 (n - 1) = 10, t = the gap here */
    struct verdict_entry a = entry(6, 0, sqrt(0.5)), b = entry(6, 2.228139, sqrt(0.5));
    CHECK_NEAR(verdict_welch_p(&a, &b), 0.05, 1e-5); /* Student's t table: t(0.975, 10) */
    b.mean = 3.169273;
    CHECK_NEAR(verdict_welch_p(&a, &b), 0.01, 1e-5);                     /* t(0.995, 10) */
    CHECK_NEAR(verdict_welch_p(&b, &a), 0.01, 1e-5);                     /* two-sided */
    b = entry(1001, 2 * 1.959964, sqrt(2)), a = entry(1001, 0, sqrt(2)); /* t = gap / 2 */
    CHECK_NEAR(verdict_welch_p(&a, &b), 0.0501, 3e-4);                   /* near the normal's 5% */
    b = entry(6, 0, 0), a = entry(6, 0, 0);
    CHECK(verdict_welch_p(&a, &b) == 1); /* no spread, same mean */
    b.mean = 1e-9;
    CHECK(verdict_welch_p(&a, &b) == 0); /* no spread, means apart */
    b = entry(1, 5, NAN);
    CHECK(verdict_welch_p(&a, &b) == 1); /* one seed: nothing to judge by */
}

/* Holm's step-down over three pairs: the smallest p against 0.05/3, the next 0.05/2, the last
   0.05; it stops at the first pair it keeps. */
static void test_holm(void)
{
    /* three variants on a line, se 1 each, 1000 seeds: p from the normal approximately */
    struct verdict_entry e[3] = {entry(1000, 0, 1), entry(1000, 3.2, 1), entry(1000, 8, 1)};
    struct verdict_ranking r = {.n = 3, .e = e};
    verdict_rank(&r);
    /* pairs: 0-1 gap 3.2/sqrt2 = 2.26 (p 0.024), 1-2 gap 3.39 (p 0.0007), 0-2 (p ~1e-8): Holm
       rejects 0-2 at 0.05/3, 1-2 at 0.05/2 and 0-1 at 0.05/1 */
    CHECK(r.status == VERDICT_CLEAR && e[0].rank == 1 && e[1].rank == 2 && e[2].rank == 3);
    struct verdict_entry f[3] = {entry(1000, 0, 1), entry(1000, 3.2, 1), entry(1000, 3.5, 1)};
    r.e = f;
    verdict_rank(&r);
    /* 0-2 p 0.013 <= 0.0167, 0-1 p 0.024 <= 0.025, 1-2 p 0.83: 1 and 2 tie behind 0 */
    CHECK(f[0].rank == 1 && f[1].rank == 2 && f[2].rank == 2 && r.status == VERDICT_CLEAR);
    struct verdict_entry g[3] = {entry(1000, 0, 1), entry(1000, 2.9, 1), entry(1000, 3.3, 1)};
    r.e = g;
    verdict_rank(&r);
    /* 0-2 p 0.0196 > 0.0167: Holm stops at the first, nothing is apart */
    CHECK(r.status == VERDICT_INCONCLUSIVE && g[2].rank == 1);
}

/* A standard normal by Box and Muller. */
static double normal(struct rng *r)
{
    double u, v;
    rng_uniform_pair(r, &u, &v);
    return sqrt(-2 * log(1 - u)) * cos(2 * M_PI * v);
}

/* The rule before this one, for comparison: apart when the gap between the means of log relMSE
   exceeds the larger of the two min-max ranges. */
static int old_apart(const struct verdict_entry *e, int nv)
{
    for (int i = 0; i < nv; i++)
        for (int j = 0; j < nv; j++) {
            double gap = log(e[j].value) - log(e[i].value);
            if (gap > fmax(log(e[i].hi / e[i].lo), log(e[j].hi / e[j].lo)))
                return 1;
        }
    return 0;
}

/* Simulate STUDIES studies of nv variants with SEEDS seeds each, variant 1's log relMSE `gap`
   standard deviations above the others; the share of studies whose ranking separates any pair
   (new rule, and *old for the rule before). */
static double separated_share(int nv, double gap, double *old, uint64_t seed)
{
    struct rng r;
    rng_seed(&r, seed, 7);
    int apart = 0, old_n = 0;
    for (int s = 0; s < STUDIES; s++) {
        struct verdict_entry e[MAXV];
        for (int v = 0; v < nv; v++) {
            verdict_entry_start(&e[v], v);
            for (int k = 0; k < SEEDS; k++)
                verdict_entry_add(&e[v], exp(-5 + (v == 1 ? gap : 0) + normal(&r)), 1);
            verdict_entry_end(&e[v], 1);
        }
        struct verdict_ranking rk = {.n = nv, .e = e};
        old_n += old_apart(e, nv);
        verdict_rank(&rk);
        apart += rk.status != VERDICT_INCONCLUSIVE;
    }
    *old = (double)old_n / STUDIES;
    return (double)apart / STUDIES;
}

static void test_error_rates(void)
{
    double old, binomial_se = sqrt(VERDICT_ALPHA * (1 - VERDICT_ALPHA) / STUDIES);
    double fp = separated_share(6, 0, &old, 1);
    printf("six identical variants, %d seeds, %d studies: P(any pair separated) = %.4f (old rule %.4f)\n",
           SEEDS, STUDIES, fp, old);
    CHECK(fp <= VERDICT_ALPHA + 3 * binomial_se);
    CHECK(fp > 0); /* the test is not blind: it does separate now and then */
    double fp2 = separated_share(2, 0, &old, 2);
    printf("two identical variants: P(separated) = %.4f (old rule %.4f)\n", fp2, old);
    CHECK(fp2 <= VERDICT_ALPHA + 3 * binomial_se);
    const double gaps[] = {1, 2, 3}, floor_power[] = {0.3, 0.85, 0.99};
    for (int i = 0; i < 3; i++) {
        double power = separated_share(2, gaps[i], &old, 10 + (uint64_t)i);
        printf("two variants %g sigma apart: power %.4f (old rule %.4f)\n", gaps[i], power, old);
        CHECK(power >= floor_power[i]);
    }
}

int main(void)
{
    test_welch_p();
    test_holm();
    test_error_rates();
    return check_report("test_verdict_rank");
}
