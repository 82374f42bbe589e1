/* pointstat: what blue-noise research measures of a 2D point set (as UTK and PSA do): the
   periodogram over integer frequencies, its radial mean and anisotropy, the minimum distance and
   the L2 star discrepancy. */
#ifndef POINTSTAT_H
#define POINTSTAT_H

#include <stddef.h>

#include "base/err.h"
#include "sampler.h"

/* Most complex multiply-adds one spectrum may take over all its sets (sets x points x
   frequencies / 2), and most point pairs pointstat_pairs may visit over all its sets: a few
   seconds of CPU each. */
#define POINTSTAT_MAX_SPECTRUM_WORK 4000000000.0
#define POINTSTAT_MAX_PAIR_WORK 2000000000.0

/* The mean periodogram P(k) = |sum_j exp(-2 pi i k.x_j)|^2 / N of the sets added, over the integer
   frequencies k in [-half, half]^2. A random set's is 1 on average at every k != 0; P(0) = N. */
struct spectrum {
    int half;        /* the window's half side K */
    int sets;        /* sets added */
    double *mean;    /* (K + 1) rows (ky = 0..K) of 2K + 1 (kx = -K..K): the sum over sets, then / sets */
    double *re, *im; /* one set's sums, same shape */
    double *ex;      /* 2 (2K + 1): exp(-2 pi i kx x) of one point, then of its y for ky = 0..K */
};

/* Window half side for a set of about n points: 2 sqrt(n) (twice a grid's first peak), at least 8. */
int spectrum_half_for(size_t n);

/* Allocate s for frequencies in [-half, half]^2, half in [1, 4096]. 0, or -1 and e filled. */
int spectrum_init(struct spectrum *s, int half, struct err *e);
void spectrum_release(struct spectrum *s);

/* Add one set of n >= 1 points to the mean. Allocates nothing; cannot fail. */
void spectrum_add(struct spectrum *s, const struct pt2 *p, size_t n);

/* The mean over the sets added at frequency (kx, ky), |kx|, |ky| <= half (P(-k) = P(k)). */
double spectrum_at(const struct spectrum *s, int kx, int ky);

/* Radial mean power and anisotropy over annuli r - 1/2 <= |k| < r + 1/2, r = 1..half (Lagae and
   Dutre 2008): mean[r - 1] the annulus's mean power, anisotropy_db[r - 1] = 10 log10 of its power's
   variance over mean^2 (0 dB for one random set: an exponential's variance is its mean^2). */
void spectrum_radial(const struct spectrum *s, double *mean, double *anisotropy_db);

/* The mean power over 0 < |k| <= k_low, k_low >= 1 (and <= half). */
double spectrum_low_mean(const struct spectrum *s, double k_low);

/* Minimum distance between two of the n points (INFINITY when n < 2): *plain in the unit square,
   *torus modulo 1 on each axis; and the L2 star discrepancy by Warnock's formula (1972):
   T^2 = 1/9 - (1 / 2N) sum_i (1 - x_i^2)(1 - y_i^2) + (1 / N^2) sum_ij (1 - max(x_i, x_j))(1 - max(y_i,
   y_j)). O(n^2): n (n - 1) / 2 pairs. */
void pointstat_pairs(const struct pt2 *p, size_t n, double *plain, double *torus, double *discrepancy);

#endif
