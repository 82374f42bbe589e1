/* pfm: encode and decode the Portable Float Map (linear float RGB, rows stored bottom to top). */
#ifndef PFM_H
#define PFM_H

#include "image.h"

/* Encode img as "PF" (colour), little-endian (scale -1.0), rows bottom to top, into a malloc'd
   buffer (*out, caller frees). 0, or -1 with e filled. */
int pfm_encode(const struct rgbf *img, uint8_t **out, size_t *out_len, struct err *e);

/* Decode a "PF" (RGB) or "Pf" (grey, copied to R, G and B) map of either byte order into out
   (row 0 at the top). `name` is used in error messages. Rejects malformed, truncated or oversized
   input (IMAGE_MAX_SIDE, IMAGE_MAX_PIXELS) with -1 and e filled. The scale's magnitude is not
   applied (pbrt and most readers ignore it). */
int pfm_decode(const uint8_t *data, size_t len, const char *name, struct rgbf *out, struct err *e);

#endif
