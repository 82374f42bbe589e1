/* errspec: the luminance error's spectrum by a separable DFT of a centred crop (errspec.h). */
#include "errspec.h"

#include <math.h>
#include <stdlib.h>

int errspec_lowfreq(const struct rgbf *ref, const struct rgbf *img, double *lowfreq, struct err *e)
{
    if (ref->w != img->w || ref->h != img->h)
        return err_set(e, NULL, 0, 0, "error spectrum: sizes differ (%dx%d against %dx%d)", img->w, img->h,
                       ref->w, ref->h);
    const int w = img->w < ERRSPEC_MAX_SIDE ? img->w : ERRSPEC_MAX_SIDE,
              h = img->h < ERRSPEC_MAX_SIDE ? img->h : ERRSPEC_MAX_SIDE;
    const int x0 = (img->w - w) / 2, y0 = (img->h - h) / 2;
    double *err_img = malloc((size_t)w * h * sizeof *err_img), *re = malloc((size_t)w * h * sizeof *re),
           *im = malloc((size_t)w * h * sizeof *im), *tw = malloc(2 * (size_t)(w > h ? w : h) * sizeof *tw);
    if (!err_img || !re || !im || !tw) {
        free(err_img), free(re), free(im), free(tw);
        return err_set(e, NULL, 0, 0, "out of memory for an error spectrum");
    }
    double mean = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const float *a = img->px + 3 * ((size_t)(y0 + y) * img->w + x0 + x),
                        *r = ref->px + 3 * ((size_t)(y0 + y) * ref->w + x0 + x);
            const double d = 0.2126 * (a[0] - r[0]) + 0.7152 * (a[1] - r[1]) + 0.0722 * (a[2] - r[2]);
            err_img[y * w + x] = d;
            mean += d / ((double)w * h);
        }
    /* rows: re + i im = sum_x e(x, y) exp(-2 pi i kx x / w), kx = 0..w-1 */
    for (int k = 0; k < w; k++)
        tw[2 * k] = cos(2 * M_PI * k / w), tw[2 * k + 1] = -sin(2 * M_PI * k / w);
    for (int y = 0; y < h; y++)
        for (int k = 0; k < w; k++) {
            double sr = 0, si = 0;
            for (int x = 0; x < w; x++) {
                const int t = (int)(((long)k * x) % w);
                sr += (err_img[y * w + x] - mean) * tw[2 * t];
                si += (err_img[y * w + x] - mean) * tw[2 * t + 1];
            }
            re[y * w + k] = sr, im[y * w + k] = si;
        }
    /* columns, then the energies by band */
    for (int k = 0; k < h; k++)
        tw[2 * k] = cos(2 * M_PI * k / h), tw[2 * k + 1] = -sin(2 * M_PI * k / h);
    double low = 0, total = 0;
    long n_low = 0, n_all = 0;
    for (int kx = 0; kx < w; kx++)
        for (int ky = 0; ky < h; ky++) {
            double sr = 0, si = 0;
            for (int y = 0; y < h; y++) {
                const int t = (int)(((long)ky * y) % h);
                sr += re[y * w + kx] * tw[2 * t] - im[y * w + kx] * tw[2 * t + 1];
                si += re[y * w + kx] * tw[2 * t + 1] + im[y * w + kx] * tw[2 * t];
            }
            if (kx == 0 && ky == 0)
                continue;
            const double fx = (kx <= w / 2 ? kx : kx - w) / (w / 2.0),
                         fy = (ky <= h / 2 ? ky : ky - h) / (h / 2.0);
            const double p = sr * sr + si * si;
            const int in_low = fx * fx + fy * fy <= ERRSPEC_LOW_RADIUS * ERRSPEC_LOW_RADIUS;
            total += p;
            n_all++;
            if (in_low)
                low += p, n_low++;
        }
    *lowfreq = n_low > 0 && total > 0 ? (low / total) / ((double)n_low / (double)n_all) : NAN;
    free(err_img), free(re), free(im), free(tw);
    return 0;
}
