/* test_pointstat: the periodogram against its definition, the spectra every sampler is known for
   (random flat at 1, jitter and Poisson low at low frequencies, Poisson's peak near 1/r), Warnock's
   discrepancy against a brute-force integral, minimum distances, and discrepancy's decay rates. */
#include "sample/pointstat.h"

#include <math.h>
#include <stdlib.h>

#include "check.h"

#define PI_ 3.14159265358979323846

/* The mean spectrum of `sets` sets of (kind, t) drawn with seeds 1..sets, over window half. */
static int mean_spectrum(enum sampler_kind kind, double t, int sets, int half, struct spectrum *sp, size_t *n)
{
    struct err e;
    struct sampler *s = sampler_new(kind, t, 0, 0, &e);
    struct pt2 *p = s ? malloc(sampler_set_capacity(s) * sizeof *p) : NULL;
    int ok = p && spectrum_init(sp, half ? half : spectrum_half_for(sampler_set_capacity(s)), &e) == 0;
    for (int k = 0; ok && k < sets; k++) {
        struct rng rng;
        rng_seed(&rng, (uint64_t)k + 1, 0);
        *n = sampler_draw(s, &rng, p);
        spectrum_add(sp, p, *n);
    }
    free(p);
    sampler_free(s);
    return ok ? 0 : -1;
}

static void test_definition(void)
{
    struct pt2 p[37];
    struct rng rng;
    rng_seed(&rng, 1, 1);
    for (int j = 0; j < 37; j++)
        p[j] = (struct pt2){rng_uniform(&rng), rng_uniform(&rng)};
    struct spectrum sp;
    struct err e;
    CHECK(spectrum_init(&sp, 70, &e) == 0);
    spectrum_add(&sp, p, 37);
    double worst = 0;
    for (int ky = -70; ky <= 70; ky += 3)
        for (int kx = -70; kx <= 70; kx++) {
            double re = 0, im = 0;
            for (int j = 0; j < 37; j++) {
                double a = -2 * PI_ * (kx * p[j].x + ky * p[j].y);
                re += cos(a);
                im += sin(a);
            }
            worst = fmax(worst, fabs(spectrum_at(&sp, kx, ky) - (re * re + im * im) / 37));
        }
    CHECK(worst < 1e-10);
    CHECK_NEAR(spectrum_at(&sp, 0, 0), 37, 1e-9); /* DC: N */
    spectrum_release(&sp);

    /* one point: |exp|^2 = 1 everywhere */
    CHECK(spectrum_init(&sp, 300, &e) == 0);
    spectrum_add(&sp, &(struct pt2){0.123456789, 0.987654321}, 1);
    worst = 0;
    for (int ky = -300; ky <= 300; ky++)
        for (int kx = -300; kx <= 300; kx++)
            worst = fmax(worst, fabs(spectrum_at(&sp, kx, ky) - 1));
    CHECK(worst < 1e-12);
    spectrum_release(&sp);
    CHECK(spectrum_init(&sp, 0, &e) == -1 && e.msg[0]);
    CHECK(spectrum_init(&sp, 5000, &e) == -1);
}

/* Random points: every k != 0 has mean power 1 and, over M sets, a mean of M exponentials (the
   pairs k, -k the same value), so an annulus's mean over c frequencies has standard error about
   sqrt(2 / (M c)). Each annulus within 5 of them, the window's mean within 4. */
static void test_random_flat(void)
{
    struct spectrum sp;
    size_t n = 0;
    const int sets = 32;
    CHECK(mean_spectrum(SAMPLER_RANDOM, 6.25, sets, 0, &sp, &n) == 0 && n == 256);
    const int K = sp.half;
    double mean[64], aniso[64];
    CHECK(K == 32);
    spectrum_radial(&sp, mean, aniso);
    int flat = 1;
    double aniso_mean = 0;
    for (int r = 1; r <= K; r++) {
        const double c = 2 * PI_ * r; /* frequencies in the annulus, about */
        flat &= fabs(mean[r - 1] - 1) < 5 * sqrt(2.0 / (sets * c));
        aniso_mean += r >= 4 ? aniso[r - 1] / (K - 3) : 0; /* the small annuli's are too noisy */
    }
    CHECK(flat);
    /* isotropic: a mean of M exponentials has variance 1 / M, -15 dB at M = 32 */
    CHECK_NEAR(aniso_mean, 10 * log10(1.0 / sets), 1.0);
    const double all = spectrum_low_mean(&sp, K);
    CHECK_NEAR(all, 1.0, 4 * sqrt(2.0 / (sets * PI_ * K * K)));
    CHECK_NEAR(spectrum_low_mean(&sp, 8), 1.0, 4 * sqrt(2.0 / (sets * PI_ * 64)));
    spectrum_release(&sp);
}

/* Jitter, Poisson and sobol: low frequencies (|k| <= sqrt(N) / 2) well below 1; Poisson's radial
   peak near 1 / r. */
static void test_blue(void)
{
    struct spectrum sp;
    size_t n = 0;
    CHECK(mean_spectrum(SAMPLER_JITTER, 6.25, 16, 0, &sp, &n) == 0);
    const double jitter_low = spectrum_low_mean(&sp, 8);
    spectrum_release(&sp);
    CHECK(mean_spectrum(SAMPLER_SOBOL, 6.25, 16, 0, &sp, &n) == 0);
    const double sobol_low = spectrum_low_mean(&sp, 8);
    spectrum_release(&sp);
    const double t = 5, r = t / 100;
    CHECK(mean_spectrum(SAMPLER_POISSON, t, 16, 40, &sp, &n) == 0);
    const double poisson_low = spectrum_low_mean(&sp, 0.5 * sqrt((double)n));
    double mean[40], aniso[40];
    spectrum_radial(&sp, mean, aniso);
    int peak = 0;
    for (int k = 1; k < 40; k++)
        peak = mean[k] > mean[peak] ? k : peak;
    spectrum_release(&sp);
    printf("low-frequency power: jitter %.3f sobol %.3f poisson %.3f; poisson peak at %d (1/r = %g), %.2f\n",
           jitter_low, sobol_low, poisson_low, peak + 1, 1 / r, mean[peak]);
    CHECK(jitter_low < 0.5);
    CHECK(sobol_low < 0.5);
    CHECK(poisson_low < 0.5);
    CHECK(peak + 1 >= 0.7 / r && peak + 1 <= 1.3 / r && mean[peak] > 1.2);
}

/* Warnock's closed form against the integral it stands for, int (#{x < u, y < v} / N - u v)^2,
   by the midpoint rule on a fine grid; and the minimum distances. */
static void test_pairs(void)
{
    struct pt2 p[7];
    struct rng rng;
    rng_seed(&rng, 2, 2);
    for (int j = 0; j < 7; j++)
        p[j] = (struct pt2){rng_uniform(&rng), rng_uniform(&rng)};
    double plain, torus, d;
    pointstat_pairs(p, 7, &plain, &torus, &d);
    const int G = 1000;
    double integral = 0;
    for (int a = 0; a < G; a++)
        for (int b = 0; b < G; b++) {
            const double u = (a + 0.5) / G, v = (b + 0.5) / G;
            int in = 0;
            for (int j = 0; j < 7; j++)
                in += p[j].x < u && p[j].y < v;
            integral += (in / 7.0 - u * v) * (in / 7.0 - u * v) / ((double)G * G);
        }
    CHECK_NEAR(d, sqrt(integral), 2e-3 * sqrt(integral));
    pointstat_pairs(&(struct pt2){0, 0}, 1, &plain, &torus, &d);
    CHECK_NEAR(d, sqrt(1.0 / 9 - 0.5 + 1), 1e-12);
    CHECK(isinf(plain) && isinf(torus));

    struct pt2 two[2] = {{0.01, 0.5}, {0.99, 0.5}};
    pointstat_pairs(two, 2, &plain, &torus, &d);
    CHECK_NEAR(plain, 0.98, 1e-12);
    CHECK_NEAR(torus, 0.02, 1e-12);
    struct pt2 grid[100];
    for (int j = 0; j < 100; j++)
        grid[j] = (struct pt2){(j % 10 + 0.5) / 10, (j / 10 + 0.5) / 10};
    pointstat_pairs(grid, 100, &plain, &torus, &d);
    CHECK_NEAR(plain, 0.1, 1e-12);
    CHECK_NEAR(torus, 0.1, 1e-12);
}

/* Least-squares slope of log mean discrepancy against log N over N = 64 .. 4096. */
static double discrepancy_slope(enum sampler_kind kind)
{
    const double t[4] = {12.5, 6.25, 3.125, 1.5625};
    double x[4], y[4], mx = 0, my = 0, sxy = 0, sxx = 0;
    for (int i = 0; i < 4; i++) {
        struct err e;
        struct sampler *s = sampler_new(kind, t[i], 0, 0, &e);
        struct pt2 *p = malloc(sampler_set_capacity(s) * sizeof *p);
        double sum = 0;
        size_t n = 0;
        const int sets = 8;
        for (int k = 0; k < sets; k++) {
            struct rng rng;
            rng_seed(&rng, (uint64_t)k + 100, 3);
            n = sampler_draw(s, &rng, p);
            double plain, torus, d;
            pointstat_pairs(p, n, &plain, &torus, &d);
            sum += d;
        }
        x[i] = log((double)n);
        y[i] = log(sum / sets);
        mx += x[i] / 4;
        my += y[i] / 4;
        free(p);
        sampler_free(s);
    }
    for (int i = 0; i < 4; i++) {
        sxy += (x[i] - mx) * (y[i] - my);
        sxx += (x[i] - mx) * (x[i] - mx);
    }
    return sxy / sxx;
}

/* L2 star discrepancy falls as N^-1/2 for random points, N^-3/4 for jittered ones and about N^-1
   (times logs) for scrambled nets and Halton points: the low-discrepancy kinds' fitted slopes at
   least 0.15 steeper than random's, the nets' steeper than jitter's. */
static void test_discrepancy_rates(void)
{
    const double random = discrepancy_slope(SAMPLER_RANDOM), jitter = discrepancy_slope(SAMPLER_JITTER),
                 sobol = discrepancy_slope(SAMPLER_SOBOL), halton = discrepancy_slope(SAMPLER_HALTON),
                 pmj = discrepancy_slope(SAMPLER_PMJ02BN), zsobol = discrepancy_slope(SAMPLER_ZSOBOL);
    printf("discrepancy slopes: random %.3f jitter %.3f sobol %.3f halton %.3f pmj02bn %.3f zsobol %.3f\n",
           random, jitter, sobol, halton, pmj, zsobol);
    CHECK_NEAR(random, -0.5, 0.1);
    CHECK(jitter < random - 0.15);
    CHECK(sobol < random - 0.15);
    CHECK(sobol < jitter);
    CHECK(halton < random - 0.15);
    CHECK(pmj < jitter && zsobol < jitter);
}

int main(void)
{
    test_definition();
    test_random_flat();
    test_blue();
    test_pairs();
    test_discrepancy_rates();
    return check_report("test_pointstat");
}
