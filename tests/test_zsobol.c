/* test_zsobol: a pixel's Z-Sobol set is one aligned block of the Sobol sequence's indices and a
   (0,m,2)-net; four pixels of one Morton quad together form the next net (the hierarchy that
   spreads the error as blue noise, measured on an integrand that varies slowly across pixels); sets
   are deterministic and differ between dimensions and seeds (test_sobol checks the 64-bit index's
   second coordinate). */
#include "sample/zsobol.h"

#include <math.h>
#include <stdlib.h>

#include "check.h"
#include "net_check.h"
#include "sample/pointstat.h"
#include "sample/sobol.h"

static void test_blocks_and_nets(void)
{
    struct pt2 p[4 * 1024];
    int blocks = 1, nets = 1, quads = 1;
    for (int m = 0; m <= 10; m++)
        for (uint32_t px = 0; px < 6; px++) {
            struct zsobol_key k = {17 + (uint64_t)m, (uint32_t)m % 3, px * 37, px * 11 + 5, m};
            const uint32_t n = (uint32_t)1 << m;
            uint64_t first = zsobol_index(k, 0) >> m;
            for (uint32_t i = 0; i < n; i++)
                blocks &= zsobol_index(k, i) >> m == first;
            zsobol_fill(k, p);
            nets &= points_are_net(p, n) == 1;
            /* the Morton quad holding this pixel: its four pixels' sets, one net of 4n */
            for (uint32_t q = 0; q < 4; q++) {
                struct zsobol_key kq = k;
                kq.x = (k.x & ~1u) | (q & 1u);
                kq.y = (k.y & ~1u) | (q >> 1);
                zsobol_fill(kq, p + q * n);
            }
            quads &= points_are_net(p, 4 * n) == 1;
        }
    CHECK(blocks);
    CHECK(nets);
    CHECK(quads);
    /* the checks can fail: a quad of pixels from different dimensions is no net */
    struct zsobol_key a = {3, 0, 8, 8, 4}, b = a;
    zsobol_fill(a, p);
    b.dim = 1;
    for (uint32_t q = 1; q < 4; q++) {
        b.x = 8 | (q & 1u);
        b.y = 8 | (q >> 1);
        b.dim = q;
        zsobol_fill(b, p + q * 16);
    }
    CHECK(points_are_net(p, 64) == 0);
}

static void test_keys(void)
{
    struct zsobol_key k = {42, 0, 5, 9, 6};
    struct pt2 a[64], b[64];
    zsobol_fill(k, a);
    zsobol_fill(k, b);
    int same = 1;
    for (int i = 0; i < 64; i++)
        same &= a[i].x == b[i].x && a[i].y == b[i].y;
    CHECK(same);
    k.dim = 1;
    zsobol_fill(k, b);
    CHECK(a[0].x != b[0].x || a[0].y != b[0].y);
    k.dim = 0;
    k.seed = 43;
    zsobol_fill(k, b);
    CHECK(a[0].x != b[0].x || a[0].y != b[0].y);
    /* an odd power of two: still a net */
    k.log2_spp = 7;
    struct pt2 c[128];
    zsobol_fill(k, c);
    CHECK(points_are_net(c, 128) == 1);
}

#define SIDE 32

/* A pixel's integrand over its sample square: a smooth bump whose centre drifts across the image. */
static double bump(struct pt2 p, int x, int y)
{
    const double c = 0.5 + 0.3 * sin(x * 0.1) + 0.2 * cos(y * 0.13);
    return exp(-4 * (p.x - c) * (p.x - c) - p.y * p.y);
}

/* The error image's power within 1/4 of the Nyquist frequency (|k| <= SIDE / 8, DC left out) as a
   share of its total, over white noise's share (the share of frequencies there): 1 for white. */
static double low_share(const double *err)
{
    double mean = 0, low = 0, total = 0;
    int n_low = 0, n_all = 0;
    for (int i = 0; i < SIDE * SIDE; i++)
        mean += err[i] / (SIDE * SIDE);
    for (int ky = -SIDE / 2; ky < SIDE / 2; ky++)
        for (int kx = -SIDE / 2; kx < SIDE / 2; kx++) {
            if (!kx && !ky)
                continue;
            double re = 0, im = 0;
            for (int y = 0; y < SIDE; y++)
                for (int x = 0; x < SIDE; x++) {
                    const double phase = -2 * M_PI * (kx * x + ky * y) / SIDE, e = err[y * SIDE + x] - mean;
                    re += e * cos(phase);
                    im += e * sin(phase);
                }
            const int is_low = kx * kx + ky * ky <= (SIDE / 8) * (SIDE / 8);
            total += re * re + im * im;
            low += is_low ? re * re + im * im : 0;
            n_low += is_low;
            n_all++;
        }
    return low / total / ((double)n_low / n_all);
}

/* Ahmed and Wonka's claim: each pixel's estimate of a slowly varying integrand from its 16 zsobol
   points errs against its neighbours' (a Morton block's points form a larger net), so the error
   image's low frequencies are nearly empty; Owen-scrambled Sobol sets drawn per pixel give white
   error. Over 4 seeds: measured 0.16 against 1.05. */
static void test_blue_error(void)
{
    static double err[SIDE * SIDE];
    struct pt2 p[16];
    double z = 0, w = 0;
    for (uint64_t seed = 1; seed <= 4; seed++)
        for (int kind = 0; kind < 2; kind++) {
            struct rng rng;
            rng_seed(&rng, seed, 5);
            for (int y = 0; y < SIDE; y++)
                for (int x = 0; x < SIDE; x++) {
                    if (kind == 0)
                        zsobol_fill((struct zsobol_key){seed, 2, (uint32_t)x, (uint32_t)y, 4}, p);
                    else
                        sobol_fill(sobol_seeds_draw(&rng), 16, p);
                    double est = 0, exact = 0;
                    for (int i = 0; i < 16; i++)
                        est += bump(p[i], x, y) / 16;
                    for (int i = 0; i < 64 * 64; i++)
                        exact +=
                            bump((struct pt2){(i % 64 + 0.5) / 64, (i / 64 + 0.5) / 64}, x, y) / (64 * 64);
                    err[y * SIDE + x] = est - exact;
                }
            *(kind == 0 ? &z : &w) += low_share(err) / 4;
        }
    printf("error_lowfreq of a smooth integrand, 16 points a pixel: zsobol %.3f, sobol per pixel %.3f\n", z,
           w);
    CHECK(z < 0.3);
    CHECK(w > 0.6 && w < 1.6);
}

/* zsobol_fill hashes each digit's permutation once per run of samples sharing the digits above
   it: its points are zsobol_point's, made one at a time from the index, bit for bit (even and
   odd log2_spp, several pixels and dimensions). */
static void test_fill_is_point(void)
{
    static struct pt2 p[1 << 9];
    int same = 1;
    for (int log2 = 0; log2 <= 9; log2++)
        for (uint32_t d = 0; d < 3; d++) {
            const struct zsobol_key k = {0x5eed + (uint64_t)log2, d, 3 + d, 17 * d, log2};
            zsobol_fill(k, p);
            for (uint32_t i = 0; i < (1u << log2); i++) {
                const struct pt2 q = zsobol_point(k, i);
                same &= q.x == p[i].x && q.y == p[i].y;
            }
        }
    CHECK(same);
}

int main(void)
{
    test_fill_is_point();
    test_blocks_and_nets();
    test_keys();
    test_blue_error();
    return check_report("test_zsobol");
}
