/* metrics: per-channel error sums over two 8-bit images scaled to [0, 1]. */
#include "metrics.h"

#include <math.h>

int metrics_compare(const struct rgb8 *ref, const struct rgb8 *img, struct metrics *m, struct err *e)
{
    if (ref->w != img->w || ref->h != img->h)
        return err_set(e, NULL, 0, 0, "image sizes differ: %dx%d against a %dx%d reference", img->w, img->h,
                       ref->w, ref->h);
    size_t n = (size_t)ref->w * ref->h * 3;
    double se = 0, rel = 0;
    for (size_t i = 0; i < n; i++) {
        double a = ref->px[i] / 255.0, b = img->px[i] / 255.0;
        double d = b - a;
        se += d * d;
        rel += d * d / (a * a + METRICS_REL_EPS);
    }
    m->mse = se / n;
    m->rmse = sqrt(m->mse);
    m->relmse = rel / n;
    m->psnr = m->mse > 0 ? 10 * log10(1.0 / m->mse) : INFINITY;
    return 0;
}
