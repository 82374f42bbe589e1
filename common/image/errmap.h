/* errmap: a false-colour picture of the per-pixel relative error of an image against a reference. */
#ifndef ERRMAP_H
#define ERRMAP_H

#include "image.h"
#include "mask.h"

/* The colour scale: log10 of a pixel's term from ERRMAP_LOG10_MIN (black) to ERRMAP_LOG10_MAX
   (pale yellow), an inferno-like ramp; a term of 0 is black, terms past the ends are clamped. */
#define ERRMAP_LOG10_MIN (-4.0)
#define ERRMAP_LOG10_MAX 2.0
/* The colour of a mask's outline. */
#define ERRMAP_OUTLINE_RGB 0, 230, 255

/* Into out (allocated here, ref's size): each pixel coloured by its relMSE term, the mean over
   R, G, B of (v - r)^2 / (r^2 + METRICS_REL_EPS), on log scale. -1 with e filled on different
   sizes or no memory. */
int errmap_make(const struct rgbf *ref, const struct rgbf *img, struct rgb8 *out, struct err *e);

/* Into out (allocated here, w x h): per-pixel FLIP values flip (w*h, in [0, 1]) on the same ramp,
   linearly from 0 (black) to 1 (pale yellow). -1 with e filled on no memory. */
int errmap_flip(const float *flip, int w, int h, struct rgb8 *out, struct err *e);

/* Mark m's outline on img (m's size): every pixel outside m next to one inside (left, right, above
   or below) turns ERRMAP_OUTLINE_RGB (cyan), so the counted pixels themselves stay as they are. */
void errmap_outline(struct rgb8 *img, const struct img_mask *m);

/* The scale in words, for the map's PNG text chunk (key ERRMAP_TEXT_KEY). */
#define ERRMAP_TEXT_KEY "worker:scale"
const char *errmap_scale_text(void);

#endif
