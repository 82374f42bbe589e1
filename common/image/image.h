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

/* Linear float RGB, row 0 at the top; px holds w*h*3 floats, owned by the struct (image_f_free). */
struct rgbf {
    int w, h;
    float *px;
};

/* PNG and PPM hold 8-bit display values (gamma 2); EXR and PFM linear float radiance. */
enum img_format { IMG_PNG, IMG_PPM, IMG_EXR, IMG_PFM };

/* What a float image's values are: linear radiance (from EXR, PFM or a framebuffer) or 8-bit
   display values v / 255 in [0, 1] (from PNG or PPM, not gamma-decoded: see imgio_read_f). */
enum img_domain { IMG_LINEAR, IMG_DISPLAY8 };

/* One string attribute a float file's header carries (EXR; PFM has nowhere to put them). */
struct img_attr {
    const char *key, *value;
};

/* Largest side any image we read or write may have. */
#define IMAGE_MAX_SIDE 32768
/* Largest pixel count (w * h) a decoder accepts, so a tiny file cannot demand gigabytes. */
#define IMAGE_MAX_PIXELS 100000000L

/* Allocate a zeroed w x h raster into img (sides 1..IMAGE_MAX_SIDE); on a bad size or no memory
   -1, img zeroed and e filled. The free functions accept NULL, a zeroed struct or one already freed. */
int image_alloc(struct rgb8 *img, int w, int h, struct err *e);
void image_free(struct rgb8 *img);

/* The same for a float raster. */
int image_f_alloc(struct rgbf *img, int w, int h, struct err *e);
void image_f_free(struct rgbf *img);

/* img's 8-bit values as display floats v / 255 into out (w x h, allocated here). 0 or -1. */
int image_f_from_rgb8(const struct rgb8 *img, struct rgbf *out, struct err *e);

/* The name of a domain for messages and JSON: "linear" or "8-bit". */
const char *image_domain_name(enum img_domain d);

/* Linear float RGB (w*h*3) to 8 bits in out (same layout): sqrt (gamma 2), clamp to [0, 0.999],
   times 256. Never fails. */
void image_float_to_rgb8(const float *rgb, int w, int h, uint8_t *out);

/* How many of img's w*h*3 values are NaN or infinite (a reference with any scores every error
   as NaN: refused where it is given). */
size_t image_f_nonfinite(const struct rgbf *img);

/* Whether no component of the w*h*3 linear floats in rgb is above 0: an entirely black image. */
int image_float_black(const float *rgb, int w, int h);

#endif
