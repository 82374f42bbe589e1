/* image: allocating 8-bit RGB rasters and converting the renderer's linear floats to them. */
#include "image.h"

#include <math.h>
#include <stdlib.h>

/* A zeroed w x h x 3 raster of `size`-byte values into *px (sides 1..IMAGE_MAX_SIDE); what names
   it in the error. 0, or -1 with e filled. */
static int raster_alloc(int w, int h, size_t size, const char *what, void **px, struct err *e)
{
    *px = NULL;
    if (w < 1 || h < 1 || w > IMAGE_MAX_SIDE || h > IMAGE_MAX_SIDE)
        return err_set(e, NULL, 0, 0, "image size %dx%d out of range (sides 1..%d)", w, h, IMAGE_MAX_SIDE);
    if (!(*px = calloc((size_t)w * (size_t)h * 3, size)))
        return err_set(e, NULL, 0, 0, "out of memory for a %dx%d %s", w, h, what);
    return 0;
}

int image_alloc(struct rgb8 *img, int w, int h, struct err *e)
{
    void *px;
    const int rc = raster_alloc(w, h, 1, "image", &px, e);
    if (rc < 0)
        w = h = 0; /* and px NULL */
    *img = (struct rgb8){w, h, px};
    return rc;
}

void image_free(struct rgb8 *img)
{
    if (img) {
        free(img->px);
        *img = (struct rgb8){0};
    }
}

int image_f_alloc(struct rgbf *img, int w, int h, struct err *e)
{
    void *px;
    const int rc = raster_alloc(w, h, sizeof(float), "float image", &px, e);
    if (rc < 0)
        w = h = 0; /* and px NULL */
    *img = (struct rgbf){w, h, px};
    return rc;
}

void image_f_free(struct rgbf *img)
{
    if (img) {
        free(img->px);
        *img = (struct rgbf){0};
    }
}

int image_f_from_rgb8(const struct rgb8 *img, struct rgbf *out, struct err *e)
{
    if (image_f_alloc(out, img->w, img->h, e) < 0)
        return -1;
    size_t n = (size_t)img->w * (size_t)img->h * 3;
    for (size_t i = 0; i < n; i++)
        out->px[i] = (float)(img->px[i] / 255.0);
    return 0;
}

const char *image_domain_name(enum img_domain d)
{
    return d == IMG_LINEAR ? "linear" : "8-bit";
}

/* One channel: NaN and negatives give 0, then gamma 2, clamp below 1, scale to 0..255. */
static uint8_t float_to_byte(float c)
{
    double v = c > 0 ? sqrt((double)c) : 0.0; /* !(c > 0) also catches NaN */
    if (v > 0.999)
        v = 0.999;
    return (uint8_t)(int)(256.0 * v);
}

void image_float_to_rgb8(const float *rgb, int w, int h, uint8_t *out)
{
    size_t n = (size_t)(w > 0 ? w : 0) * (size_t)(h > 0 ? h : 0) * 3;
    for (size_t i = 0; i < n; i++)
        out[i] = float_to_byte(rgb[i]);
}

size_t image_f_nonfinite(const struct rgbf *img)
{
    size_t bad = 0, n = (size_t)(img->w > 0 ? img->w : 0) * (size_t)(img->h > 0 ? img->h : 0) * 3;
    for (size_t i = 0; i < n; i++)
        bad += !isfinite(img->px[i]);
    return bad;
}

int image_float_black(const float *rgb, int w, int h)
{
    size_t n = (size_t)(w > 0 ? w : 0) * (size_t)(h > 0 ? h : 0) * 3;
    for (size_t i = 0; i < n; i++)
        if (rgb[i] > 0)
            return 0;
    return 1;
}
