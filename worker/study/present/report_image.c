/* report_image: the compare report's image analysis (zoom, worst window, crops, colour bar). */
#include "report_image.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image/errmap.h"
#include "image/metrics.h"

int report_image_zoom(int w, int target_px)
{
    int zoom = w > 0 ? (target_px + w - 1) / w : 2;
    return zoom < 2 ? 2 : zoom;
}

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

int report_image_crop(const struct rgb8 *src, int x0, int y0, int side, struct rgb8 *out, struct err *e)
{
    if (image_alloc(out, side, side, e) < 0)
        return -1;
    for (int y = 0; y < side; y++)
        memcpy(&out->px[(size_t)y * side * 3], &src->px[((size_t)(y0 + y) * src->w + x0) * 3],
               (size_t)side * 3);
    return 0;
}

/* Against a black reference the term of a grey value v is v^2 / METRICS_REL_EPS, so
   v = sqrt(eps 10^L) gives exactly 10^L. */
int report_image_errmap_bar(int w, struct rgb8 *out, struct err *e)
{
    struct rgbf ref = {0}, img = {0};
    int rc = -1;
    if (image_f_alloc(&ref, w, 1, e) < 0 || image_f_alloc(&img, w, 1, e) < 0)
        goto done;
    for (int i = 0; i < w; i++) {
        double l = ERRMAP_LOG10_MIN + (ERRMAP_LOG10_MAX - ERRMAP_LOG10_MIN) * (i + 0.5) / w;
        img.px[3 * i] = img.px[3 * i + 1] = img.px[3 * i + 2] = (float)sqrt(METRICS_REL_EPS * pow(10, l));
    }
    rc = errmap_make(&ref, &img, out, e);
done:
    image_f_free(&ref);
    image_f_free(&img);
    return rc;
}
