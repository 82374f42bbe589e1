/* test_sobol: the Sobol generator matrices against their textbook definition, the Owen scramble's
   tree structure, the (0,m,2)-net property of every power-of-two set, the sobol sampler's sizes and
   determinism, and its error's convergence rate. */
#include "sample/sobol.h"

#include "sample/pointstat.h"

#include "base/simd.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "net_check.h"

/* Sobol's second dimension the long way: direction numbers v_1 = 1/2, v_(k+1) = v_k xor v_k / 2
   (primitive polynomial x + 1), xored for each set bit of i. */
static uint32_t sobol_y_textbook(uint64_t i)
{
    uint32_t v = 0x80000000u, r = 0;
    for (; i; i >>= 1, v ^= v >> 1)
        if (i & 1)
            r ^= v;
    return r;
}

/* The radical inverse in base 2, digit by digit. */
static uint32_t van_der_corput_textbook(uint32_t i)
{
    uint32_t r = 0;
    for (int k = 0; k < 32; k++)
        if (i & (1u << k))
            r |= 1u << (31 - k);
    return r;
}

static void test_generators(void)
{
    struct rng rng;
    rng_seed(&rng, 5, 0);
    int same = 1;
    for (uint32_t i = 0; i < 4096; i++)
        same &= sobol_x(i) == van_der_corput_textbook(i) && sobol_y(i) == sobol_y_textbook(i);
    for (int k = 0; k < 10000; k++) {
        uint32_t i = rng_u32(&rng);
        same &= sobol_x(i) == van_der_corput_textbook(i) && sobol_y(i) == sobol_y_textbook(i);
    }
    CHECK(same);
    /* the sequence's start: 0, 1/2, then (1/4, 3/4), (3/4, 1/4) */
    CHECK(sobol_x(0) == 0 && sobol_y(0) == 0);
    CHECK(sobol_x(1) == 0x80000000u && sobol_y(1) == 0x80000000u);
    CHECK(sobol_x(2) == 0x40000000u && sobol_y(2) == 0xc0000000u);
    CHECK(sobol_x(3) == 0xc0000000u && sobol_y(3) == 0x40000000u);
}

/* A 64-bit index (zsobol's): the second coordinate of lo + 2^32 hi is sobol_y(lo) ^ sobol_y(hi), as
   Pascal's matrix's columns 32.. repeat its columns 0.. in the first 32 digits. */
static void test_high_index(void)
{
    struct rng rng;
    rng_seed(&rng, 8, 0);
    int same = 1;
    for (int k = 0; k < 20000; k++) {
        const uint64_t i = (uint64_t)rng_u32(&rng) << 24 ^ rng_u32(&rng);
        same &= (sobol_y((uint32_t)i) ^ sobol_y((uint32_t)(i >> 32))) == sobol_y_textbook(i);
    }
    CHECK(same);
}

/* Owen's scramble is a tree of flips: two values that share their first d digits still share
   them after it, and their digit d + 1 differs after it iff it differed before. */
static void test_owen_tree(void)
{
    struct rng rng;
    rng_seed(&rng, 6, 0);
    int tree = 1, moved = 0;
    for (int k = 0; k < 20000; k++) {
        uint32_t seed = rng_u32(&rng), a = rng_u32(&rng), d = rng_below(&rng, 32);
        uint32_t below = d < 31 ? rng_u32(&rng) >> (d + 1) : 0;
        uint32_t b = a ^ (0x80000000u >> d) ^ below; /* the same first d digits, then another */
        uint32_t sa = sobol_owen(a, seed), sb = sobol_owen(b, seed);
        uint32_t top = d ? ~0u << (32 - d) : 0;
        tree &= (sa & top) == (sb & top) && ((sa ^ sb) & (0x80000000u >> d)) != 0;
        moved += sa != a;
    }
    CHECK(tree);
    CHECK(moved > 19000); /* it does scramble */
    /* a bijection: 2^16 values with fixed low bits stay distinct */
    uint8_t *seen = calloc(1u << 16, 1);
    int distinct = seen != NULL;
    for (uint32_t v = 0; seen && v < (1u << 16); v++) {
        uint32_t s = sobol_owen(v << 16, 12345u) >> 16;
        distinct &= !seen[s];
        seen[s] = 1;
    }
    CHECK(distinct);
    free(seen);
}

/* A block's points (a table lookup for the shuffled index's low part), one coordinate at a time
   and side by side (AVX2, where the processor has it), are sobol_point's, bit for bit, at every
   size from 2 to 2^14 and for random seeds. */
static void test_block(void)
{
    uint64_t *table = malloc(((size_t)1 << 14) * sizeof *table);
    struct rng rng;
    rng_seed(&rng, 11, 0);
    int same = table != NULL, high_varies = 0;
    const int wide = simd_avx2();
    for (int bits = 1; table && bits <= 14; bits++) {
        sobol_low_table(table, bits);
        for (int set = 0; set < 8; set++) {
            const struct sobol_seeds seeds = sobol_seeds_draw(&rng);
            const struct sobol_block b = sobol_block_of(seeds, bits);
            high_varies += b.hi[0] != 0;
            for (uint32_t k = 0; k < 1u << bits; k++) {
                const struct pt2 p = sobol_block_point(&b, table, bits, sobol_bit_reverse(k)),
                                 w = wide ? sobol_block_point_wide(&b, table, bits, sobol_bit_reverse(k)) : p,
                                 q = sobol_point(seeds, k);
                same &= p.x == q.x && p.y == q.y && w.x == q.x && w.y == q.y;
            }
        }
    }
    CHECK(same);
    CHECK(high_varies > 100);
    free(table);
}

static int is_net(const struct pt2 *p, size_t n, int m)
{
    return n == (size_t)1 << m && points_are_net(p, n) == 1;
}

static void test_nets(void)
{
    struct pt2 *p = malloc(((size_t)1 << 14) * sizeof *p);
    struct rng rng;
    rng_seed(&rng, 7, 0);
    int nets = 1, prefixes = 1;
    for (int m = 0; m <= 14; m++)
        for (int s = 0; s < 4; s++) {
            sobol_fill(sobol_seeds_draw(&rng), (size_t)1 << m, p);
            nets &= is_net(p, (size_t)1 << m, m);
            for (int k = 0; k < m; k++) /* every power-of-two prefix is a net too */
                prefixes &= is_net(p, (size_t)1 << k, k);
        }
    CHECK(nets);
    CHECK(prefixes);

    /* a broken set is caught: two points swapped in y */
    sobol_fill(sobol_seeds_draw(&rng), 256, p);
    double y = p[0].y;
    p[0].y = p[1].y;
    p[1].y = y;
    CHECK(!is_net(p, 256, 8));
    free(p);
}

/* The sampler: n = floor(100 / t)^2 points, all in [0, 1), a net when n is a power of two,
   drawn whole (no cells) or point by point (sampler_sobol_set, sobol_point), the same set for
   the same rng state and another for another. */
static void test_sampler(void)
{
    enum sampler_kind kind;
    CHECK(sampler_kind_parse("sobol", &kind) == 0 && kind == SAMPLER_SOBOL);
    CHECK(strcmp(sampler_kind_name(SAMPLER_SOBOL), "sobol") == 0);
    CHECK(sampler_capacity(SAMPLER_SOBOL, 6.25) == 256 && sampler_capacity(SAMPLER_SOBOL, 3) == 1089);
    struct err e;
    const double t[] = {100, 50, 25, 12.5, 6.25, 3.125, 1.5625, 3, 7, 0.9};
    struct pt2 *a = malloc(12345 * sizeof *a), *b = malloc(12345 * sizeof *b);
    for (size_t k = 0; k < sizeof t / sizeof t[0]; k++) {
        struct sampler *s = sampler_new(SAMPLER_SOBOL, t[k], 0, 0, &e);
        CHECK(s != NULL && sampler_cells(s) == 0 && sampler_kind_of(s) == SAMPLER_SOBOL);
        const int side = sampler_grid_side(t[k]);
        const size_t n = (size_t)side * (size_t)side;
        struct rng r1, r2, r3;
        rng_seed(&r1, 3, 9);
        rng_seed(&r2, 3, 9);
        rng_seed(&r3, 4, 9);
        CHECK(sampler_draw(s, &r1, a) == n && sampler_draw(s, &r2, b) == n);
        CHECK(memcmp(a, b, n * sizeof *a) == 0 && r1.state == r2.state);
        int inside = 1;
        for (size_t i = 0; i < n; i++)
            inside &= a[i].x >= 0 && a[i].x < 1 && a[i].y >= 0 && a[i].y < 1;
        CHECK(inside);
        if ((n & (n - 1)) == 0)
            CHECK(is_net(a, n, (int)round(log2((double)n))));
        sampler_draw(s, &r3, b);
        CHECK(n == 1 || memcmp(a, b, n * sizeof *a) != 0);
        /* the set point by point (a light's sets): the same count, rng draws and points, bit for bit */
        struct sobol_seeds seeds;
        rng_seed(&r3, 3, 9);
        CHECK(sampler_sobol_set(s, &r3, &seeds) == n && r3.state == r1.state);
        int same = 1;
        for (size_t i = n; i-- > 0;) {
            const struct pt2 q = sobol_point(seeds, (uint32_t)i);
            same &= memcmp(&q, &a[i], sizeof q) == 0;
        }
        CHECK(same);
        sampler_free(s);
    }
    free(a);
    free(b);
}

/* Unbiased and fast: over many scrambles the mean of a quarter disk's indicator is its area, and
   the mean squared error falls as N^-1.5 on it (Owen 1997's rate for scrambled nets on a
   discontinuous integrand, jitter's), N^-1 for random points (steeper by at least 0.3). */
static void test_convergence(void)
{
    const double r2 = 0.63661977236758134308; /* 2 / pi: the disk covers half the square */
    double log_n[4], log_mse[4], bias_z = 0;
    struct pt2 *p = malloc(((size_t)1 << 14) * sizeof *p);
    struct rng rng;
    rng_seed(&rng, 8, 0);
    const int sets = 1024;
    for (int i = 0; i < 4; i++) {
        const size_t n = (size_t)1 << (8 + 2 * i);
        double se = 0, sum = 0;
        for (int s = 0; s < sets; s++) {
            sobol_fill(sobol_seeds_draw(&rng), n, p);
            double in = 0;
            for (size_t k = 0; k < n; k++)
                in += p[k].x * p[k].x + p[k].y * p[k].y < r2;
            se += (in / n - 0.5) * (in / n - 0.5);
            sum += in / n - 0.5;
        }
        log_n[i] = log((double)n);
        log_mse[i] = log(se / sets);
        /* the mean error in standard errors of the mean */
        bias_z = fmax(bias_z, fabs(sum / sets) / sqrt(se / sets / sets));
    }
    double mx = 0, my = 0, sxy = 0, sxx = 0;
    for (int i = 0; i < 4; i++) {
        mx += log_n[i] / 4;
        my += log_mse[i] / 4;
    }
    for (int i = 0; i < 4; i++) {
        sxy += (log_n[i] - mx) * (log_mse[i] - my);
        sxx += (log_n[i] - mx) * (log_n[i] - mx);
    }
    CHECK_NEAR(sxy / sxx, -1.5, 0.15);
    CHECK(bias_z < 4.5);
    free(p);
}

int main(void)
{
    test_generators();
    test_high_index();
    test_owen_tree();
    test_block();
    test_nets();
    test_sampler();
    test_convergence();
    return check_report("test_sobol");
}
