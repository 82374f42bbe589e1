/* pointstat: periodogram, radial power and anisotropy, minimum distance, L2 star discrepancy. */
#include "pointstat.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"

int spectrum_half_for(size_t n)
{
    int k = (int)ceil(2.0 * sqrt((double)n));
    return k < 8 ? 8 : k;
}

int spectrum_init(struct spectrum *s, int half, struct err *e)
{
    memset(s, 0, sizeof *s);
    if (half < 1 || half > 4096)
        return err_set(e, NULL, 0, 0, "spectrum: window half side must be in [1, 4096], got %d", half);
    const size_t cells = (size_t)(half + 1) * (size_t)(2 * half + 1);
    s->half = half;
    s->mean = calloc(cells, sizeof *s->mean);
    s->re = malloc(cells * sizeof *s->re);
    s->im = malloc(cells * sizeof *s->im);
    s->ex = malloc(4 * ((size_t)2 * half + 1) * sizeof *s->ex);
    if (!s->mean || !s->re || !s->im || !s->ex) {
        spectrum_release(s);
        return err_set(e, NULL, 0, 0, "out of memory for a %dx%d spectrum", 2 * half + 1, 2 * half + 1);
    }
    return 0;
}

void spectrum_release(struct spectrum *s)
{
    free(s->mean);
    free(s->re);
    free(s->im);
    free(s->ex);
    memset(s, 0, sizeof *s);
}

/* exp(-2 pi i k t) for k = -K..K into c (re) and c + 2K + 1 (im), index k + K, t in [0, 1): powers
   of one phasor, made afresh from sin and cos every 64 steps so rounding cannot build up. */
static void phasors(double t, int K, double *c)
{
    const int side = 2 * K + 1;
    double *re = c, *im = c + side;
    double s1, c1, r = 1.0, i = 0.0;
    v3_sincos_turn(t, &s1, &c1);
    re[K] = 1.0;
    im[K] = 0.0;
    for (int k = 1; k <= K; k++) {
        if (k % 64 == 0) {
            const double turn = (double)k * t;
            double sk, ck;
            v3_sincos_turn(turn - floor(turn), &sk, &ck);
            r = ck;
            i = -sk;
        } else {
            const double r0 = r;
            r = r0 * c1 + i * s1; /* (r + i I)(cos - sin I) */
            i = i * c1 - r0 * s1;
        }
        re[K + k] = r;
        im[K + k] = i;
        re[K - k] = r;
        im[K - k] = -i;
    }
}

void spectrum_add(struct spectrum *s, const struct pt2 *p, size_t n)
{
    const int K = s->half, side = 2 * K + 1;
    const size_t cells = (size_t)(K + 1) * (size_t)side;
    memset(s->re, 0, cells * sizeof *s->re);
    memset(s->im, 0, cells * sizeof *s->im);
    double *xr = s->ex, *xi = s->ex + side, *yr = s->ex + 2 * side, *yi = s->ex + 3 * side;
    for (size_t j = 0; j < n; j++) {
        phasors(p[j].x, K, xr);
        phasors(p[j].y, K, yr);
        for (int ky = 0; ky <= K; ky++) {
            const double ar = yr[K + ky], ai = yi[K + ky];
            double *re = s->re + (size_t)ky * side, *im = s->im + (size_t)ky * side;
            for (int kx = 0; kx < side; kx++) {
                re[kx] += ar * xr[kx] - ai * xi[kx];
                im[kx] += ar * xi[kx] + ai * xr[kx];
            }
        }
    }
    for (size_t c = 0; c < cells; c++)
        s->mean[c] += (s->re[c] * s->re[c] + s->im[c] * s->im[c]) / (double)n;
    s->sets++;
}

double spectrum_at(const struct spectrum *s, int kx, int ky)
{
    if (ky < 0) {
        kx = -kx;
        ky = -ky;
    }
    return s->sets ? s->mean[(size_t)ky * (2 * s->half + 1) + (size_t)(kx + s->half)] / s->sets : 0.0;
}

void spectrum_radial(const struct spectrum *s, double *mean, double *anisotropy_db)
{
    const int K = s->half;
    for (int r = 1; r <= K; r++) {
        double sum = 0, sum2 = 0;
        long count = 0;
        for (int ky = -K; ky <= K; ky++)
            for (int kx = -K; kx <= K; kx++) {
                const double len = sqrt((double)kx * kx + (double)ky * ky);
                if (len < r - 0.5 || len >= r + 0.5)
                    continue;
                const double v = spectrum_at(s, kx, ky);
                sum += v;
                sum2 += v * v;
                count++;
            }
        const double m = count ? sum / count : 0.0;
        const double var = count > 1 ? fmax(0.0, (sum2 - count * m * m) / (count - 1)) : 0.0;
        mean[r - 1] = m;
        anisotropy_db[r - 1] = m > 0 && var > 0 ? 10.0 * log10(var / (m * m)) : -INFINITY;
    }
}

double spectrum_low_mean(const struct spectrum *s, double k_low)
{
    const int K = s->half;
    double sum = 0;
    long count = 0;
    for (int ky = -K; ky <= K; ky++)
        for (int kx = -K; kx <= K; kx++) {
            const double len2 = (double)kx * kx + (double)ky * ky;
            if (len2 > 0 && len2 <= k_low * k_low) {
                sum += spectrum_at(s, kx, ky);
                count++;
            }
        }
    return count ? sum / count : 0.0;
}

void pointstat_pairs(const struct pt2 *p, size_t n, double *plain, double *torus, double *discrepancy)
{
    double best = INFINITY, best_torus = INFINITY, single = 0, pairs = 0;
    for (size_t i = 0; i < n; i++) {
        const double xi = p[i].x, yi = p[i].y;
        single += (1 - xi * xi) * (1 - yi * yi);
        pairs += (1 - xi) * (1 - yi); /* the j = i term */
        double row = 0;
        for (size_t j = i + 1; j < n; j++) {
            const double dx = fabs(xi - p[j].x), dy = fabs(yi - p[j].y);
            const double tx = fmin(dx, 1 - dx), ty = fmin(dy, 1 - dy);
            best = fmin(best, dx * dx + dy * dy);
            best_torus = fmin(best_torus, tx * tx + ty * ty);
            row += (1 - fmax(xi, p[j].x)) * (1 - fmax(yi, p[j].y));
        }
        pairs += 2 * row;
    }
    *plain = sqrt(best);
    *torus = sqrt(best_torus);
    const double N = (double)n;
    const double t2 = n ? 1.0 / 9.0 - single / (2.0 * N) + pairs / (N * N) : 0.0;
    *discrepancy = sqrt(fmax(0.0, t2));
}
