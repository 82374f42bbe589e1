/* image: 8-bit RGB rasters and the float-to-8-bit conversion (gamma 2, as the RTOW books). */
#ifndef IMAGE_H
#define IMAGE_H

#include <stddef.h>
#include <stdint.h>

#include "base/err.h"

/* Row 0 at the top; px holds w*h*3 bytes, owned by the struct (image_free). */
struct rgb8 {
    int w, h;
    uint8_t *px;
};

enum img_format { IMG_PNG, IMG_PPM };

/* Largest side any image we read or write may have. */
#define IMAGE_MAX_SIDE 32768
/* Largest pixel count (w * h) a decoder accepts, so a tiny file cannot demand gigabytes. */
#define IMAGE_MAX_PIXELS 100000000L

/* Allocate a zeroed w x h raster; -1 and e filled on bad size or no memory. */
int image_alloc(struct rgb8 *img, int w, int h, struct err *e);
void image_free(struct rgb8 *img);

/* Linear float RGB (w*h*3) to 8 bits: sqrt (gamma 2), clamp to [0, 0.999], times 256. */
void image_float_to_rgb8(const float *rgb, int w, int h, uint8_t *out);

/* Whether no component of the w*h*3 linear floats in rgb is above 0: an entirely black image. */
int image_float_black(const float *rgb, int w, int h);

#endif
