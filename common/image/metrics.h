/* metrics: error of an image against a reference (MSE, RMSE, relMSE as pbrt, its firefly-robust
   variant, PSNR), on linear radiance or on 8-bit display values. */
#ifndef METRICS_H
#define METRICS_H

#include "image.h"
#include "mask.h"

/* All per channel value, averaged over the w*h*3 values: mse = mean (v - r)^2; relmse = mean
   (v - r)^2 / (r^2 + METRICS_REL_EPS) (not pbrt-v4's MRSE, which divides by (r + eps)^2); relmse_robust =
   relmse with the largest METRICS_ROBUST_DROP of the per-pixel terms (a pixel's term: the mean of its three
   channels') left out, none below 1000 pixels (a few fireflies otherwise decide the figure, as in the path
   guiding papers); psnr = 10 log10(1 / mse), peak 1 = display white, in dB (inf when equal). */
struct metrics {
    double mse, rmse, relmse, relmse_robust, psnr;
};

#define METRICS_REL_EPS 0.01
#define METRICS_ROBUST_DROP 0.001

/* Error of img against ref (same size), both floats of one domain, between the means of
   block x block tiles (edge tiles clipped; block 1 = per pixel): averaging k pixels divides
   independent noise's RMSE by about sqrt(k) while a change over a large area keeps its size.
   -1 with e filled on different sizes, block < 1, a non-finite value or no memory. */
int metrics_compare_f(const struct rgbf *ref, const struct rgbf *img, int block, struct metrics *m,
                      struct err *e);

/* metrics_compare_f over mask's pixels only (every pixel when mask is NULL): a tile's means take
   its counted pixels, a tile without any is left out, so with block 1 the figures are those of
   the counted pixels alone (a rectangle's: the cropped images'). -1 with e filled as
   metrics_compare_f, or when mask is not the images' size. */
int metrics_compare_masked(const struct rgbf *ref, const struct rgbf *img, int block,
                           const struct img_mask *mask, struct metrics *m, struct err *e);

/* The display metrics: the same figures on two 8-bit images' values v / 255 (what a PNG viewer
   shows, clipped and gamma-encoded: not radiance). -1 with e filled as metrics_compare_f. */
int metrics_display_compare(const struct rgb8 *ref, const struct rgb8 *img, struct metrics *m, struct err *e);

/* metrics_display_compare over mask's pixels (all when NULL), as metrics_compare_masked. */
int metrics_display_masked(const struct rgb8 *ref, const struct rgb8 *img, const struct img_mask *mask,
                           struct metrics *m, struct err *e);

#endif
