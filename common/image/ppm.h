/* ppm: encode P6 and decode P3/P6 netpbm images in memory. */
#ifndef PPM_H
#define PPM_H

#include "image.h"

/* Encode img as binary P6 (maxval 255) into a malloc'd buffer (*out, caller frees). */
int ppm_encode(const struct rgb8 *img, uint8_t **out, size_t *out_len, struct err *e);

/* Decode P3 or P6 data (len bytes; `name` for messages; maxval 1..65535, scaled to 8 bits,
   comments allowed) into out. 0, or -1 with e filled (a header error at its line and column) and
   out zeroed on malformed, truncated or oversized input. */
int ppm_decode(const uint8_t *data, size_t len, const char *name, struct rgb8 *out, struct err *e);

/* The width and height ppm_decode would give, from the header alone (nothing allocated). 0, or -1
   with e filled as ppm_decode fills it. */
int ppm_size(const uint8_t *data, size_t len, const char *name, int *w, int *h, struct err *e);

#endif
