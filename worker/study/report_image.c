/* report_image: the compare report's image analysis (worst window, zoomed crops, error maps). */
#include "report_image.h"

#include <stdlib.h>
#include <string.h>

#include "image/metrics.h"

/* The square window (side `side`) with the largest summed relative squared error of the
   images against ref: where samplers differ most (a soft shadow in our scenes). */
void report_image_worst_window(const struct rgb8 *ref, const struct rgb8 *imgs, int n, int side, int *bx,
                               int *by)
{
    int w = ref->w, h = ref->h;
    double *sat = calloc((size_t)(w + 1) * (h + 1), sizeof *sat); /* summed-area table */
    *bx = (w - side) / 2, *by = (h - side) / 2;
    if (!sat)
        return;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double v = 0;
            for (int i = 0; i < n; i++)
                for (int ch = 0; ch < 3; ch++) {
                    size_t k = ((size_t)y * w + x) * 3 + ch;
                    double a = ref->px[k] / 255.0, d = imgs[i].px[k] / 255.0 - a;
                    v += d * d / (a * a + METRICS_REL_EPS);
                }
            sat[(size_t)(y + 1) * (w + 1) + x + 1] = v + sat[(size_t)y * (w + 1) + x + 1] +
                                                     sat[(size_t)(y + 1) * (w + 1) + x] -
                                                     sat[(size_t)y * (w + 1) + x];
        }
    double best = -1;
    int step = side / 4 > 1 ? side / 4 : 1;
    for (int y = 0; y + side <= h; y += step)
        for (int x = 0; x + side <= w; x += step) {
            double v = sat[(size_t)(y + side) * (w + 1) + x + side] - sat[(size_t)y * (w + 1) + x + side] -
                       sat[(size_t)(y + side) * (w + 1) + x] + sat[(size_t)y * (w + 1) + x];
            if (v > best)
                best = v, *bx = x, *by = y;
        }
    free(sat);
}

/* out = the side x side window of src at (x0, y0), each pixel repeated REPORT_IMAGE_CROP_ZOOM times. */
int report_image_crop_zoom(const struct rgb8 *src, int x0, int y0, int side, struct rgb8 *out, struct err *e)
{
    if (image_alloc(out, side * REPORT_IMAGE_CROP_ZOOM, side * REPORT_IMAGE_CROP_ZOOM, e) < 0)
        return -1;
    for (int y = 0; y < out->h; y++)
        for (int x = 0; x < out->w; x++)
            memcpy(&out->px[((size_t)y * out->w + x) * 3],
                   &src->px[((size_t)(y0 + y / REPORT_IMAGE_CROP_ZOOM) * src->w + x0 +
                             x / REPORT_IMAGE_CROP_ZOOM) *
                            3],
                   3);
    return 0;
}

/* The error maps' gain at one sweep point, the same for every variant so they compare: the
   99th percentile of |image - reference| over all their pixels and channels shows white. A
   fixed gain left converged images' maps black, hiding where a method still fails. */
int report_image_error_gain(const struct rgb8 *ref, const struct rgb8 *imgs, int n)
{
    size_t count[256] = {0}, total = (size_t)ref->w * ref->h * 3 * n, seen = 0;
    for (int i = 0; i < n; i++)
        for (size_t k = 0; k < (size_t)ref->w * ref->h * 3; k++)
            count[abs((int)imgs[i].px[k] - (int)ref->px[k])]++;
    int q = 0;
    while (q < 255 && (seen += count[q]) < total - total / 100)
        q++;
    int gain = q > 0 ? 255 / q : REPORT_IMAGE_GAIN_MAX;
    return gain < 1 ? 1 : gain > REPORT_IMAGE_GAIN_MAX ? REPORT_IMAGE_GAIN_MAX : gain;
}

/* out = |img - ref| x gain per channel, clamped: structure in the error shows as a pattern. */
int report_image_error_map(const struct rgb8 *ref, const struct rgb8 *img, int gain, struct rgb8 *out,
                           struct err *e)
{
    if (image_alloc(out, ref->w, ref->h, e) < 0)
        return -1;
    for (size_t k = 0; k < (size_t)ref->w * ref->h * 3; k++) {
        int d = abs((int)img->px[k] - (int)ref->px[k]) * gain;
        out->px[k] = (uint8_t)(d > 255 ? 255 : d);
    }
    return 0;
}
