/* report_image: what the compare report computes from its images: the window where they differ
   most from the reference, zoomed crops of it, and error maps with a gain shared by a row. */
#ifndef REPORT_IMAGE_H
#define REPORT_IMAGE_H

#include "base/err.h"
#include "image/image.h"

/* A crop's pixels are repeated this many times each way (nearest neighbour). */
#define REPORT_IMAGE_CROP_ZOOM 4
/* The error maps' largest gain (a map of images equal to the reference). */
#define REPORT_IMAGE_GAIN_MAX 64

/* The side x side window, on a grid of side / 4 steps, with the largest summed relative squared
   error (eps METRICS_REL_EPS) of the n images against ref, into (*bx, *by): where samplers
   differ most (a soft shadow in our scenes). The centred window when memory runs out. */
void report_image_worst_window(const struct rgb8 *ref, const struct rgb8 *imgs, int n, int side, int *bx,
                               int *by);

/* out = the side x side window of src at (x0, y0), each pixel repeated REPORT_IMAGE_CROP_ZOOM times
   (out allocated here; the caller frees it). */
int report_image_crop_zoom(const struct rgb8 *src, int x0, int y0, int side, struct rgb8 *out, struct err *e);

/* The gain for one row of error maps, the same for every image so they compare: 255 over the
   99th percentile of |image - reference| over all pixels and channels, in [1, REPORT_IMAGE_GAIN_MAX]. */
int report_image_error_gain(const struct rgb8 *ref, const struct rgb8 *imgs, int n);

/* out = |img - ref| x gain per channel, clamped to 255 (out allocated here). */
int report_image_error_map(const struct rgb8 *ref, const struct rgb8 *img, int gain, struct rgb8 *out,
                           struct err *e);

#endif
