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

/* The error's look pooled over images (Heck, Schloemer and Deussen 2013 and UTK show point sets'
   spectra so): radially averaged power, peaks and anisotropy of the summed periodogram. */
#define ERRSPEC_RINGS 16   /* rings of 1/16 of the Nyquist radius (the corners beyond it left out) */
#define ERRSPEC_RING_MIN 8 /* a ring with fewer frequencies has no mean to judge a peak against */
/* Structured error: a peak whose chance bound is below ERRSPEC_PEAK_P, or an anisotropy above
   ERRSPEC_ANISOTROPY (noise from any sampler that treats directions alike stays near 1). */
#define ERRSPEC_PEAK_P 1e-3
#define ERRSPEC_ANISOTROPY 2
struct errspec_look {
    double ring[ERRSPEC_RINGS]; /* each ring's mean power over the mean over all rings (white: 1); NAN
                                   for a ring without frequencies */
    double peak;                /* the largest frequency's power over its ring's mean */
    double peak_p;              /* a bound on the chance of so large a peak in noise without structure
                                   (each frequency's pooled power a mean of n exponentials about its
                                   ring's: Chernoff's bound, times the frequencies tested) */
    double anisotropy;          /* the most over the least of four orientations' (0, 45, 90, 135
                                   degrees) ring-normalised mean power, over the outer three quarters of
                                   the rings: 1 isotropic */
};

/* Add the periodogram of img's luminance error against ref (same size; the crop errspec_lowfreq
   measures) to acc (ERRSPEC_MAX_SIDE^2 doubles, the caller's, zeroed before the first), the crop's
   size into w, h. 0, or -1 with e filled (sizes differ, no memory). */
int errspec_power_add(const struct rgbf *ref, const struct rgbf *img, double *acc, int *w, int *h,
                      struct err *e);

/* The look of acc, a periodogram summed over n images (w x h). Cannot fail. */
void errspec_look_of(const double *acc, int w, int h, int n, struct errspec_look *out);

#endif
