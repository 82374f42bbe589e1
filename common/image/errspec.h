/* errspec: how an image's error looks, not only how large it is: the power spectrum of its
   luminance error (image minus reference) and the share of the error's energy at low frequencies
   against white noise's (blue-noise error, Georgiev and Fajardo 2016, Ahmed and Wonka 2020, puts
   less there at the same size). */
#ifndef ERRSPEC_H
#define ERRSPEC_H

#include "base/err.h"
#include "image.h"

/* The error image is measured on a centred crop of at most this many pixels a side (the DFT's cost
   grows as the side cubed). */
#define ERRSPEC_MAX_SIDE 128
/* The low band: frequencies within 1/8 of the Nyquist frequency (radius in units of Nyquist,
   sqrt((kx / (w/2))^2 + (ky / (h/2))^2) <= 1/8). */
#define ERRSPEC_LOW_RADIUS 0.125

/* error_lowfreq of img against ref (same size): the share of the mean-free luminance error's
   spectral energy in the low band, over the share of frequencies there (the expected share of
   white noise): 1 for white error, below 1 for blue, above for blotchy. NaN when the crop has no
   frequency in the band (sides under 16) or no error at all. 0, or -1 with e filled (sizes
   differ, no memory). */
int errspec_lowfreq(const struct rgbf *ref, const struct rgbf *img, double *lowfreq, struct err *e);

#endif
