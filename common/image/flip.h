/* flip: FLIP, the difference a person sees when two images alternate, per pixel in [0, 1] (0: none).
   LDR-FLIP (display images) is Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom and Fairchild,
   "FLIP: A Difference Evaluator for Alternating Images", HPG 2020; HDR-FLIP (linear radiance: the
   maximum of LDR-FLIP over a range of exposures tone mapped with ACES) is Andersson, Nilsson,
   Shirley and Akenine-Moller, "Visualizing Errors in Rendered High Dynamic Range Images", EG 2021,
   as Andersson, Nilsson and Akenine-Moller give both in "Visualizing and Communicating Errors in
   Rendered Images", Ray Tracing Gems II, 2021. Written from those texts. */
#ifndef FLIP_H
#define FLIP_H

#include "base/err.h"
#include "image.h"
#include "mask.h"

/* The observer of the papers: a 0.7 m wide monitor of 3840 pixels seen from 0.7 m, 0.7 * (3840 /
   0.7) * pi / 180 = 67.02 pixels per degree of visual angle. */
#define FLIP_PPD (3840.0 * 3.14159265358979323846 / 180.0)
/* Most exposures HDR-FLIP takes: a reference spanning more stops has them spread further apart. */
#define FLIP_MAX_EXPOSURES 32

struct flip_result {
    double mean;                          /* mean FLIP over the counted pixels */
    int hdr;                              /* 1: HDR-FLIP, 0: LDR-FLIP */
    double start_exposure, stop_exposure; /* HDR-FLIP's exposures, in stops (log2 of the scale) */
    int n_exposures;                      /* HDR-FLIP: how many, evenly from start to stop; LDR: 0 */
};

/* LDR-FLIP of img against ref (same size), both sRGB-encoded display values in [0, 1] (an 8-bit
   image's v / 255). Every pixel is filtered with its neighbours; the mean counts m's pixels (all
   when m is NULL). map: NULL, or w*h floats filled with the per-pixel FLIP. 0, or -1 with e filled
   (sizes differ, a non-finite value, no memory). */
int flip_ldr(const struct rgbf *ref, const struct rgbf *img, const struct img_mask *m, float *map,
             struct flip_result *out, struct err *e);

/* HDR-FLIP of img against ref, both linear radiance (negative values count as 0): exposures from
   the reference's luminance over m's pixels (start: the brightest maps to 0.85 after the tone
   mapper; stop: the median does; max(2, ceil(stop - start)) of them), LDR-FLIP of each exposure's
   tone-mapped pair, the per-pixel maximum. As flip_ldr otherwise. */
int flip_hdr(const struct rgbf *ref, const struct rgbf *img, const struct img_mask *m, float *map,
             struct flip_result *out, struct err *e);

#endif
