/* exr: encode and decode OpenEXR images in memory through OpenEXRCore's C API (openexr.h). */
#ifndef EXR_IMAGE_H
#define EXR_IMAGE_H

#include "image.h"

/* The largest EXR file exr_image_decode's callers should read (imgio bounds its reads by it). */
#define EXR_MAX_BYTES ((size_t)1 << 30)
/* The most header attributes a file read may have (all parts together). */
#define EXR_MAX_ATTRIBUTES 10000

/* Encode img as a single-part scanline EXR, channels R, G, B as 32-bit float, ZIP compression,
   with nattrs string attributes (keys must not be OpenEXR's required ones) into a malloc'd
   buffer (*out, caller frees). The bytes depend only on img and attrs. 0, or -1 with e filled.
   (OpenEXR owns the exr_ prefix; exr_image_ is not among its names.) */
int exr_image_encode(const struct rgbf *img, const struct img_attr *attrs, size_t nattrs, uint8_t **out,
                     size_t *out_len, struct err *e);

/* Decode a single-part EXR held in data[0..len) (a multipart one is refused, not cut to its first
   part; at most EXR_MAX_ATTRIBUTES header attributes): scanline storage, channels R, G and B
   (half or float; others ignored) in any compression the library decodes, the data window's size
   within IMAGE_MAX_SIDE and IMAGE_MAX_PIXELS, into out (row 0 = the window's top). `name` is used
   in messages. -1 with e filled on anything else (tiled, deep, truncated, corrupt). */
int exr_image_decode(const uint8_t *data, size_t len, const char *name, struct rgbf *out, struct err *e);

#endif
