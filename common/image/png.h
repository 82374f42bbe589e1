/* png: encode and decode PNG in memory with zlib (PNG spec, ISO/IEC 15948). */
#ifndef PNG_H
#define PNG_H

#include "image.h"

/* Encode img as 8-bit RGB PNG into a malloc'd buffer (*out, caller frees). 0 or -1. */
int png_encode(const struct rgb8 *img, uint8_t **out, size_t *out_len, struct err *e);

/* png_encode with one tEXt chunk per texts[i] (key 1..79 Latin-1 bytes, value) after IHDR. */
int png_encode_text(const struct rgb8 *img, const struct img_attr *texts, size_t ntexts, uint8_t **out,
                    size_t *out_len, struct err *e);

/* Decode a gray, gray+alpha, RGB, RGBA or palette PNG of any allowed bit depth (1 to 16), plain or
   Adam7-interlaced, into out (RGB, 8 bits; alpha dropped, 16-bit samples rounded to 8; ancillary
   chunks ignored). `name` is used in error messages. Never reads out of bounds; rejects truncated or
   corrupt data and sides over IMAGE_MAX_SIDE with -1, e filled and out zeroed. */
int png_decode(const uint8_t *data, size_t len, const char *name, struct rgb8 *out, struct err *e);

/* The width and height in data's IHDR (the signature and that first chunk checked, nothing
   allocated): what png_decode would give when the rest is sound. 0, or -1 with e filled. */
int png_size(const uint8_t *data, size_t len, const char *name, int *w, int *h, struct err *e);

#endif
