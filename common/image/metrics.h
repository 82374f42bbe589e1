/* metrics: error of an image against a reference (MSE, RMSE, relMSE as pbrt, PSNR). */
#ifndef METRICS_H
#define METRICS_H

#include "image.h"

struct metrics {
    double mse, rmse, relmse, psnr; /* on values in [0, 1]; psnr in dB (inf when equal) */
};

/* relMSE epsilon, as pbrt's imgtool: mean of (b - a)^2 / (a^2 + eps). */
#define METRICS_REL_EPS 0.01

/* Error of img against ref (same size, else -1 with e filled). */
int metrics_compare(const struct rgb8 *ref, const struct rgb8 *img, struct metrics *m, struct err *e);

/* The same error between the means of block x block tiles (edge tiles clipped); block 1 is
   metrics_compare. Averaging k pixels divides independent noise's RMSE by about sqrt(k) while
   a change over a large area keeps its size. -1 with e filled on different sizes or block < 1. */
int metrics_compare_blocks(const struct rgb8 *ref, const struct rgb8 *img, int block, struct metrics *m,
                           struct err *e);

#endif
