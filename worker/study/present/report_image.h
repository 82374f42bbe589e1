/* report_image: what the compare report computes from its images: the zoom it shows them at, the
   window where they differ most from the reference, crops of it, and the error maps' colour bar. */
#ifndef REPORT_IMAGE_H
#define REPORT_IMAGE_H

#include "base/err.h"
#include "image/image.h"

/* The width the report aims for: renders, references and error maps at least this wide, crops
   at least REPORT_IMAGE_CROP_PX (six crops fit a row of the page). */
#define REPORT_IMAGE_SHOW_PX 256
#define REPORT_IMAGE_CROP_PX 160

/* The integer zoom for an image w pixels wide: the smallest giving at least target_px, and never
   below 2, so every image pixel is a visible block of whole screen pixels. */
int report_image_zoom(int w, int target_px);

/* The side x side window, on a grid of side / 4 steps, with the largest summed relative squared
   error (eps METRICS_REL_EPS) of the n images against ref, into (*bx, *by): where samplers
   differ most (a soft shadow in our scenes). The centred window when memory runs out. */
void report_image_worst_window(const struct rgb8 *ref, const struct rgb8 *imgs, int n, int side, int *bx,
                               int *by);

/* out = the side x side window of src at (x0, y0), pixel for pixel (out allocated here; the
   caller frees it). The page zooms it. */
int report_image_crop(const struct rgb8 *src, int x0, int y0, int side, struct rgb8 *out, struct err *e);

/* out = a w x 1 strip of errmap_make's colours, column i for the term 10^L at L going evenly from
   ERRMAP_LOG10_MIN (left edge) to ERRMAP_LOG10_MAX (right edge), sampled at pixel centres: the
   error maps' colour bar, drawn by the maps' own colouring (out allocated here). */
int report_image_errmap_bar(int w, struct rgb8 *out, struct err *e);

#endif
