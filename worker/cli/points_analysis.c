/* points_analysis: `worker points`'s --spectrum, --radial and --stats over --sets sets. */
#include "points_analysis.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/err.h"
#include "base/fileio.h"
#include "image/png.h"
#include "sample/pointstat.h"
#include "study/present/chart.h"

/* The periodogram picture's log scale: log10 power from SPECTRUM_LOG_LO (black) to SPECTRUM_LOG_HI
   (white), the same for every sampler so pictures compare; white noise (1) is two thirds grey. */
#define SPECTRUM_LOG_LO -2.0
#define SPECTRUM_LOG_HI 1.0
#define SPECTRUM_MIN_PICTURE 512 /* pixels: a small window is drawn in square blocks */

int points_analysis_wanted(const struct points_analysis *a)
{
    return a->spectrum_path || a->radial_path || a->stats;
}

/* The statistics' low frequencies: 0 < |k| <= sqrt(N) / 2, below a grid's first peak (sqrt(N)). */
static double low_frequency(size_t n)
{
    double k = 0.5 * sqrt((double)n);
    return k < 1 ? 1 : k;
}

/* The periodogram's window: the full one for a picture or a chart, only the low frequencies for
   the statistics alone. */
static int window_half(const struct points_analysis *a, size_t n)
{
    if (a->spectrum_path || a->radial_path)
        return spectrum_half_for(n);
    return (int)ceil(low_frequency(n));
}

int points_analysis_check(const struct points_analysis *a, size_t n)
{
    if (!points_analysis_wanted(a))
        return 0;
    const double pairs = (double)a->sets * (double)n * ((double)n - 1) / 2;
    if (a->stats && pairs > POINTSTAT_MAX_PAIR_WORK) {
        err_print("worker points: --stats on %d set(s) of %zu points is %.3g point pairs (limit %.3g): use a "
                  "larger threshold or fewer --sets\n",
                  a->sets, n, pairs, POINTSTAT_MAX_PAIR_WORK);
        return 2;
    }
    const double K = window_half(a, n);
    const double work = (double)a->sets * (double)n * (2 * K + 1) * (K + 1);
    if (work > POINTSTAT_MAX_SPECTRUM_WORK) {
        err_print("worker points: the spectrum of %d set(s) of %zu points over %.0fx%.0f frequencies is "
                  "%.3g multiply-adds (limit %.3g): use a larger threshold or fewer --sets\n",
                  a->sets, n, 2 * K + 1, 2 * K + 1, work, POINTSTAT_MAX_SPECTRUM_WORK);
        return 2;
    }
    return 0;
}

static int report(const char *what, const struct err *e)
{
    char line[2048];
    err_format(e, line, sizeof line);
    err_print("worker points: %s: %s\n", what, line);
    return 1;
}

/* The mean periodogram as a PNG: ky up, DC at the centre, log10 power on SPECTRUM_LOG_*. */
static int write_spectrum(const char *path, const struct spectrum *sp, struct err *e)
{
    const int K = sp->half, side = 2 * K + 1;
    const int scale = side >= SPECTRUM_MIN_PICTURE ? 1 : (SPECTRUM_MIN_PICTURE + side - 1) / side;
    struct rgb8 img;
    if (image_alloc(&img, side * scale, side * scale, e) != 0)
        return -1;
    for (int row = 0; row < img.h; row++)
        for (int col = 0; col < img.w; col++) {
            const double p = spectrum_at(sp, col / scale - K, K - row / scale);
            double v = (log10(fmax(p, 1e-300)) - SPECTRUM_LOG_LO) / (SPECTRUM_LOG_HI - SPECTRUM_LOG_LO);
            v = v < 0 ? 0 : v > 1 ? 1 : v;
            uint8_t *px = img.px + 3 * ((size_t)row * img.w + col);
            px[0] = px[1] = px[2] = (uint8_t)lround(255 * v);
        }
    uint8_t *png = NULL;
    size_t len = 0;
    int rc = png_encode(&img, &png, &len, e);
    image_free(&img);
    if (rc == 0)
        rc = fileio_write_atomic(path, png, len, e);
    free(png);
    return rc;
}

/* Radial mean power and anisotropy against frequency, two log-log panels, with what random
   points give for reference (power 1; variance / mean^2 = 1 / M). */
static int write_radial(const char *path, const struct points_analysis *a, const char *name,
                        const struct spectrum *sp, struct err *e)
{
    const int K = sp->half;
    double *f = malloc(3 * (size_t)K * sizeof *f);
    if (!f)
        return err_set(e, path, 0, 0, "out of memory for the radial chart");
    double *power = f + K, *ratio = f + 2 * K;
    spectrum_radial(sp, power, ratio);
    for (int r = 0; r < K; r++) {
        f[r] = r + 1;
        ratio[r] = pow(10, ratio[r] / 10); /* dB back to variance / mean^2 */
    }
    const double one[2] = {1, 1}, random_ratio[2] = {1.0 / a->sets, 1.0 / a->sets}, ends[2] = {1, K};
    char label[160], title[256];
    snprintf(label, sizeof label, "%s t=%g", name, a->threshold);
    char ref_one[64], ref_sets[64]; /* the random sampler's expected lines */
    snprintf(ref_one, sizeof ref_one, "%s: 1", sampler_kind_name(SAMPLER_RANDOM));
    snprintf(ref_sets, sizeof ref_sets, "%s: 1 / sets", sampler_kind_name(SAMPLER_RANDOM));
    const struct chart_series pw[2] = {{label, K, f, power, NULL, NULL}, {ref_one, 2, ends, one, NULL, NULL}};
    const struct chart_series an[2] = {{label, K, f, ratio, NULL, NULL},
                                       {ref_sets, 2, ends, random_ratio, NULL, NULL}};
    const struct chart_panel panels[2] = {{"radial mean power", "frequency |k| (cycles per unit)",
                                           "mean periodogram", "no power", pw, 2, NULL, 0},
                                          {"anisotropy", "frequency |k| (cycles per unit)",
                                           "variance / mean^2 in the annulus", "no power", an, 2, NULL, 0}};
    char seeds[64]; /* the whole range: the title said "seeds 1.." */
    if (a->sets == 1)
        snprintf(seeds, sizeof seeds, "1 set, seed %llu", (unsigned long long)a->seed);
    else
        snprintf(seeds, sizeof seeds, "%d sets, seeds %llu..%llu", a->sets, (unsigned long long)a->seed,
                 (unsigned long long)(a->seed + (uint64_t)(a->sets - 1)));
    snprintf(title, sizeof title, "%s, threshold %g: radial spectrum over %s", name, a->threshold, seeds);
    char *svg = chart_svg(title, panels, 2, 2);
    free(f);
    if (!svg)
        return err_set(e, path, 0, 0, "out of memory for the radial chart");
    int rc = fileio_write_atomic(path, svg, strlen(svg), e);
    free(svg);
    return rc;
}

int points_analysis_run(const struct points_analysis *a, struct sampler *s, struct pt2 *buf)
{
    const char *name = sampler_kind_name(sampler_kind_of(s));
    struct spectrum sp = {0};
    struct err e;
    int rc = 0;
    size_t n_min = SIZE_MAX, n_max = 0;
    double n_sum = 0, plain_sum = 0, plain_min = INFINITY, torus_sum = 0, torus_min = INFINITY, disc_sum = 0;
    double k_low = 1;
    for (int k = 0; k < a->sets; k++) {
        struct rng rng;
        rng_seed(&rng, a->seed + (uint64_t)k, 0);
        const size_t n = sampler_draw(s, &rng, buf);
        if (k == 0) {
            k_low = low_frequency(n);
            if (spectrum_init(&sp, window_half(a, n), &e) != 0)
                return report("spectrum", &e);
        }
        spectrum_add(&sp, buf, n);
        n_min = n < n_min ? n : n_min;
        n_max = n > n_max ? n : n_max;
        n_sum += (double)n;
        if (a->stats) {
            double plain, torus, disc;
            pointstat_pairs(buf, n, &plain, &torus, &disc);
            plain_sum += plain;
            torus_sum += torus;
            plain_min = fmin(plain_min, plain);
            torus_min = fmin(torus_min, torus);
            disc_sum += disc;
        }
    }
    if (a->spectrum_path && write_spectrum(a->spectrum_path, &sp, &e) != 0)
        rc = report("--spectrum", &e);
    if (rc == 0 && a->radial_path && write_radial(a->radial_path, a, name, &sp, &e) != 0)
        rc = report("--radial", &e);
    if (rc == 0 && a->stats) {
        const double m = a->sets, n_mean = n_sum / m;
        printf("sampler %s\nthreshold %g\n", name, a->threshold);
        printf("sets %d (seeds %llu..%llu)\n", a->sets, (unsigned long long)a->seed,
               (unsigned long long)(a->seed + (uint64_t)(a->sets - 1)));
        if (n_min == n_max)
            printf("count %zu\n", n_min);
        else
            printf("count %.1f (mean over the sets; min %zu, max %zu)\n", n_mean, n_min, n_max);
        printf("min_distance %.6g (in the unit square, not toroidal; mean over the sets, smallest %.6g)\n",
               plain_sum / m, plain_min);
        printf("min_distance_toroidal %.6g (modulo 1 on each axis; mean over the sets, smallest %.6g)\n",
               torus_sum / m, torus_min);
        printf("star_discrepancy_l2 %.6g (Warnock's formula; mean over the sets)\n", disc_sum / m);
        printf("low_frequency_power %.6g (mean periodogram over 0 < |k| <= %.3g = sqrt(N) / 2 of the first "
               "set; %s "
               "points: 1)\n",
               spectrum_low_mean(&sp, k_low), k_low, sampler_kind_name(SAMPLER_RANDOM));
        if (fflush(stdout) != 0 || ferror(stdout)) {
            err_print("worker points: writing the statistics failed\n");
            rc = 1;
        }
    }
    spectrum_release(&sp);
    return rc;
}
