/* test_dims: sampler_dims: all's padded sets (sample/padding.h). A grid set gives the pixel's
   n samples one point in each cell; different slots and pixels give different orders; and the
   order is a uniform permutation: chi-square tests of joint strata pass for every grid 2x2 ..
   20x20, where the keyed permutation used before issue 26 (no offset, no mixing of high bits
   into low ones) fails them. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sample/padding.h"
#include "sample/sobol.h"

/* The permutation sampler_dims: all used before issue 26: keyed steps without Kensler's offset
   and without mixing the high bits into the low ones (kept here as the control the test must
   reject). */
static uint32_t old_permute(uint32_t i, uint32_t n, uint64_t key)
{
    uint32_t mask = n - 1;
    mask |= mask >> 1, mask |= mask >> 2, mask |= mask >> 4, mask |= mask >> 8, mask |= mask >> 16;
    const uint32_t k0 = (uint32_t)key, k1 = (uint32_t)(key >> 32);
    do {
        i = (i ^ k0) & mask;
        i = (i * 0x9e3779b1u) & mask;
        i ^= i >> 7;
        i = (i + k1) & mask;
        i = (i * 0x85ebca6bu) & mask;
        i ^= i >> 11;
        i = (i * 0xc2b2ae35u) & mask;
        i ^= i >> 5;
    } while (i >= n);
    return i;
}

/* Chi-square statistic of a table of counts against a uniform expectation, as a z-score by
   Wilson and Hilferty's cube-root approximation (df degrees of freedom). */
static double chi2_z(const uint32_t *count, size_t cells, double expected, double df)
{
    double x2 = 0;
    for (size_t c = 0; c < cells; c++)
        x2 += (count[c] - expected) * (count[c] - expected) / expected;
    const double a = 2.0 / (9.0 * df);
    return (cbrt(x2 / df) - (1 - a)) / sqrt(a);
}

/* Pearson's X^2 of an n x n table of n^2 counts against 1 per cell. */
static double x2_unit(const uint32_t *t, int n)
{
    double x2 = 0;
    for (int c = 0; c < n * n; c++)
        x2 += ((double)t[c] - 1) * ((double)t[c] - 1);
    return x2;
}

/* The padded cells of samples 0 .. N-1 of slots 2 and 3 for pixel k: the old keyed permutation
   (old != 0, the key its pixel had) or the padding's (pad over a uniform n x n sampler: a
   point's cell read back from its centre). */
static void padded_cells(struct padding *pad, int old, int n, int k, uint32_t *a, uint32_t *b)
{
    const uint32_t N = (uint32_t)(n * n);
    if (old) {
        const uint64_t pk = rng_mix64(1 ^ rng_mix64(((uint64_t)(uint32_t)k << 32) + 16));
        const uint64_t ka = rng_mix64(pk + 3 * 0x9e3779b97f4a7c15ULL),
                       kb = rng_mix64(pk + 4 * 0x9e3779b97f4a7c15ULL);
        for (uint32_t s = 0; s < N; s++)
            a[s] = old_permute(s, N, ka), b[s] = old_permute(s, N, kb);
        return;
    }
    padding_pixel(pad, 1, k, 0, N);
    for (uint32_t s = 0; s < N; s++) {
        struct pt2 p = padding_point(pad, 2, s), q = padding_point(pad, 3, s);
        a[s] = (uint32_t)((int)(p.y * n) * n + (int)(p.x * n));
        b[s] = (uint32_t)((int)(q.y * n) * n + (int)(q.x * n));
    }
}

/* The largest |z| of the tests over `keys` pixels of an n x n grid (N = n^2 cells; sample s of
   the pixel's own set lies in cell s):
   (1) sample index s vs its padded cell, an N x N table summed over the pixels, against the
       uniform K/N per entry ((N - 1)^2 degrees of freedom, margins fixed);
   (2) per pixel, joint strata: the pixel's column vs the padded column, row vs row, and two
       padded slots' columns against each other, each an n x n table of n^2 samples with margins
       n. For a uniform permutation Pearson's X^2 of such a table has mean (n - 1)^2 N / (N - 1)
       exactly (fixed margins); the pixels' mean X^2 against it, in standard errors of the mean.
       A permutation whose column fixes the column (4 of 16 strata at 4x4) gives 48 against 9.6. */
static double joint_strata_z(int old, int n, int keys)
{
    const uint32_t N = (uint32_t)(n * n);
    uint32_t *idx = calloc((size_t)N * N, sizeof *idx), t[3][400], pa[400], pb[400];
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0}, z = INFINITY;
    struct err e;
    struct sampler *u = sampler_new(SAMPLER_UNIFORM, 100.0 / n, 0, 0, &e);
    struct padding pad;
    if (!idx || !u || padding_init(&pad, u, 4, &e) < 0) {
        free(idx);
        sampler_free(u);
        return z;
    }
    for (int k = 0; k < keys; k++) {
        padded_cells(&pad, old, n, k, pa, pb);
        memset(t, 0, sizeof t);
        for (uint32_t s = 0; s < N; s++) {
            const uint32_t a = pa[s], b = pb[s];
            idx[(size_t)s * N + a]++;
            t[0][(s % n) * n + a % n]++;
            t[1][(s / n) * n + a / n]++;
            t[2][(a % n) * n + b % n]++;
        }
        for (int q = 0; q < 3; q++) {
            const double x2 = x2_unit(t[q], n);
            sum[q] += x2, sum2[q] += x2 * x2;
        }
    }
    z = chi2_z(idx, (size_t)N * N, (double)keys / N, (double)(N - 1) * (N - 1));
    const double mean_x2 = (double)(n - 1) * (n - 1) * N / (N - 1);
    for (int q = 0; q < 3; q++) {
        const double m = sum[q] / keys, var = (sum2[q] / keys - m * m) * keys / (keys - 1);
        const double se = sqrt(fmax(var, 1e-12) / keys);
        z = fmax(z, fabs(m - mean_x2) / se);
    }
    free(idx);
    padding_release(&pad);
    sampler_free(u);
    return z;
}

static void test_uniform_permutation(void)
{
    /* alpha 1e-4 per test (the aggregate one-sided, z > 3.72; the per-pixel ones two-sided,
       |z| > 3.89: 3.72 kept for all, a little stricter), four tests per grid, 19 grids: a
       family-wise false alarm rate under 1%; the keys are fixed, so the answer is too */
    const double z_crit = 3.72;
    int old_rejected = 0;
    for (int n = 2; n <= 20; n++) {
        const int keys = n * n * 8 > 400 ? n * n * 8 : 400; /* >= 8 per cell of the N x N table */
        const double z_new = joint_strata_z(0, n, keys);
        const double z_old = joint_strata_z(1, n, keys);
        printf("%2dx%-2d joint strata z: new %7.2f old %9.2f\n", n, n, z_new, z_old);
        CHECK(z_new < z_crit);
        old_rejected += z_old >= z_crit;
    }
    /* the control: the old permutation fails at every grid (issue 26 measured 3x3, 4x4, 5x5,
       10x10) */
    CHECK(old_rejected == 19);
}

/* Jitter and uniform sets padded: every cell once per slot, each slot in its own order. */
static void test_one_per_cell(void)
{
    struct err e;
    const enum sampler_kind kinds[] = {SAMPLER_JITTER, SAMPLER_UNIFORM};
    for (int k = 0; k < 2; k++) {
        struct sampler *s = sampler_new(kinds[k], 10, 0, 0, &e); /* 10 x 10 */
        struct padding pad;
        CHECK(s != NULL);
        if (!s || padding_init(&pad, s, 8, &e) < 0)
            continue;
        int apart = 0;
        for (int px = 0; px < 100; px++) {
            padding_pixel(&pad, 1, px, 7, 100);
            for (int slot = 0; slot < (px < 3 ? 8 : 0); slot++) {
                int count[100] = {0}, ok = 1;
                for (uint32_t i = 0; i < 100; i++) {
                    struct pt2 p = padding_point(&pad, slot, i);
                    ok &= p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1;
                    if (ok)
                        count[(int)(p.y * 10) * 10 + (int)(p.x * 10)]++;
                }
                for (int c = 0; c < 100; c++)
                    ok &= count[c] == 1;
                CHECK(ok);
            }
            /* two slots of one pixel put sample 0 in different cells for most pixels */
            struct pt2 a = padding_point(&pad, 2, 0), b = padding_point(&pad, 3, 0);
            apart += (int)(a.x * 10) != (int)(b.x * 10) || (int)(a.y * 10) != (int)(b.y * 10);
        }
        CHECK(apart > 90);
        padding_release(&pad);
        sampler_free(s);
    }
}

/* A Sobol slot makes its points as they are read: each is, bit for bit, the point the whole set
   (the slot stream's seeds, sobol_fill) left at that place after the Fisher-Yates shuffle, read in
   any order; for sets of 64, 100, 625 and 1089 points (the shuffle's draws in blocks of 64, a
   remainder, an index table of 7, 10 and 11 bits), the pixel's count the set's or fewer. */
static void test_sobol_lazy(void)
{
    static const double thresholds[] = {12.5, 10, 4, 3};
    static struct pt2 whole[1089];
    int same = 1, sizes = 0;
    for (int t = 0; t < 4; t++) {
        struct err e;
        struct sampler *s = sampler_new(SAMPLER_SOBOL, thresholds[t], 0, 0, &e);
        struct padding pad;
        CHECK(s != NULL);
        if (!s || padding_init(&pad, s, 6, &e) < 0)
            return;
        CHECK(pad.sobol != NULL && pad.pts == NULL);
        const size_t have = sampler_set_capacity(s);
        sizes += have == (size_t[]){64, 100, 625, 1089}[t];
        for (int px = 0; px < 12; px++) {
            const size_t n = px % 3 == 2 ? have - 5 - (size_t)px : have; /* the pixel's count */
            padding_pixel(&pad, 9, px, 3, n);
            for (int slot = 5; slot >= 0; slot--) {
                struct rng r;
                struct sobol_seeds seeds;
                rng_pixel(&r, 9, px, 3, 16 + (uint64_t)slot);
                CHECK(sampler_sobol_set(s, &r, &seeds) == have);
                sobol_fill(seeds, have, whole);
                for (size_t k = 0; k < have; k++) {
                    size_t j = k + rng_below(&r, (uint32_t)(have - k));
                    struct pt2 tmp = whole[k];
                    whole[k] = whole[j];
                    whole[j] = tmp;
                }
                for (uint32_t i = 0; i < n; i++) {
                    uint32_t k = (uint32_t)((i * 37 + (uint32_t)px) % n); /* any order */
                    struct pt2 p = padding_point(&pad, slot, k);
                    same &= p.x == whole[k].x && p.y == whole[k].y;
                }
            }
        }
        padding_release(&pad);
        sampler_free(s);
    }
    CHECK(same);
    CHECK(sizes == 4);
}

int main(void)
{
    test_sobol_lazy();
    test_one_per_cell();
    test_uniform_permutation();
    return check_report("test_dims");
}
