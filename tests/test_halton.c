/* test_halton: pbrt-v4's per-pixel index (each pixel's first index lands in that pixel), the
   scrambled radical inverse (a permutation per digit: b^k consecutive indices fill the b^k
   strata; uniform over seeds), the pixel sets' points inside [0, 1) and deterministic, and the
   same bits whatever the permutation cache held before. */
#include "sample/halton.h"

#include <stdlib.h>

#include "check.h"

/* floor(b^k times the radical inverse of i in base b): i's first k digits in base b, reversed. */
static uint32_t leading_digits(uint32_t b, int k, uint64_t i)
{
    uint32_t r = 0;
    for (int j = 0; j < k; j++, i /= b)
        r = r * b + (uint32_t)(i % b);
    return r;
}

static void test_pixel_offsets(void)
{
    int lands = 1, bounded = 1;
    for (uint32_t y = 0; y < HALTON_TILE_Y; y++)
        for (uint32_t x = 0; x < HALTON_TILE_X; x++) {
            const uint64_t o = halton_pixel_offset(x, y);
            bounded &= o < HALTON_STRIDE;
            /* and every later sample of the pixel too: stride 2^7 3^5 keeps those digits */
            for (uint64_t i = o; i < o + 3 * HALTON_STRIDE; i += HALTON_STRIDE)
                lands &= leading_digits(2, 7, i) == x && leading_digits(3, 5, i) == y;
        }
    CHECK(bounded);
    CHECK(lands);
    CHECK(halton_pixel_offset(130, 250) == halton_pixel_offset(2, 7)); /* the tile repeats */
}

static void test_scramble(void)
{
    const uint32_t bases[4] = {2, 3, 7, 311};
    int strata = 1, inside = 1;
    for (int t = 0; t < 4; t++) {
        const uint32_t b = bases[t], n = b == 311 ? b : b * b * b;
        unsigned char *hit = calloc(n, 1);
        for (uint64_t seed = 0; seed < 5; seed++) {
            for (uint32_t i = 0; i < n; i++)
                hit[i] = 0;
            for (uint64_t i = 0; i < n; i++) {
                const double v = halton_radical_inverse(b, i + 5 * n, seed);
                inside &= v >= 0 && v < 1;
                hit[(uint32_t)(v * n)]++;
            }
            for (uint32_t i = 0; i < n; i++)
                strata &= hit[i] == 1;
        }
        free(hit);
    }
    CHECK(strata);
    CHECK(inside);
    /* one index over many seeds: uniform (mean 1/2, variance 1/12) */
    double sum = 0, sum2 = 0;
    const int seeds = 20000;
    for (int s = 0; s < seeds; s++) {
        const double v = halton_radical_inverse(5, 12345, (uint64_t)s);
        sum += v;
        sum2 += v * v;
    }
    CHECK_NEAR(sum / seeds, 0.5, 4 * sqrt(1.0 / 12 / seeds));
    CHECK_NEAR(sum2 / seeds - (sum / seeds) * (sum / seeds), 1.0 / 12, 0.004);
}

static void test_sets(void)
{
    struct halton_cache c;
    CHECK(halton_cache_init(&c) == 0);
    struct halton_key k = {9, 0, 40, 17};
    struct pt2 a[100], b[100];
    halton_fill(&c, k, 100, a);
    halton_fill(&c, k, 100, b);
    int same = 1, inside = 1;
    for (int i = 0; i < 100; i++) {
        same &= a[i].x == b[i].x && a[i].y == b[i].y;
        inside &= a[i].x >= 0 && a[i].x < 1 && a[i].y >= 0 && a[i].y < 1;
    }
    CHECK(same && inside);
    /* dimension 3: not confined to a strip (its bases share no digit with the pixel's) */
    k.dim = 3;
    halton_fill(&c, k, 100, b);
    double lo = 1, hi = 0;
    for (int i = 0; i < 100; i++) {
        lo = fmin(lo, b[i].x);
        hi = fmax(hi, b[i].x);
    }
    CHECK(lo < 0.05 && hi > 0.95);
    halton_cache_release(&c);
}

/* The tables are functions of (seed, dim): a set is the same from a fresh cache and from one that
   has met 1000 other dimensions and the same ones of another seed (and so started over several
   times); dimensions 1 and 32 share their bases but not their points. */
static void test_cache(void)
{
    struct halton_cache fresh, busy;
    CHECK(halton_cache_init(&fresh) == 0 && halton_cache_init(&busy) == 0);
    struct pt2 a[64], b[64], junk[4];
    int same = 1;
    for (uint32_t dim = 0; dim < 40; dim++) {
        const struct halton_key k = {77, dim * 37 % 41, 5, 9};
        for (uint32_t other = 0; other < 25; other++)
            halton_fill(&busy, (struct halton_key){77 + other % 3, 1000 + dim * 25 + other, 1, 2}, 4, junk);
        halton_fill(&busy, (struct halton_key){78, k.dim, 5, 9}, 4, junk); /* another seed's */
        halton_fill(&fresh, k, 64, a);
        halton_fill(&busy, k, 64, b);
        for (uint32_t i = 0; i < 64; i++)
            same &= a[i].x == b[i].x && a[i].y == b[i].y;
    }
    CHECK(same);
    halton_fill(&fresh, (struct halton_key){77, 1, 5, 9}, 64, a);
    halton_fill(&fresh, (struct halton_key){77, 32, 5, 9}, 64, b);
    int differ = 0;
    for (int i = 0; i < 64; i++)
        differ += a[i].x != b[i].x;
    CHECK(differ > 32);
    halton_cache_release(&fresh);
    halton_cache_release(&busy);
}

int main(void)
{
    test_pixel_offsets();
    test_scramble();
    test_sets();
    test_cache();
    return check_report("test_halton");
}
