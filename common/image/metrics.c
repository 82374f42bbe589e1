/* metrics: per-channel error sums over two 8-bit images scaled to [0, 1], optionally between
   the means of block x block tiles (a box filter that averages Monte Carlo noise away). */
#include "metrics.h"

#include <math.h>

/* Mean of channel c over the tile at (x0, y0), clipped to the image. */
static double tile_mean(const struct rgb8 *img, int x0, int y0, int block, int c)
{
    int x1 = x0 + block < img->w ? x0 + block : img->w, y1 = y0 + block < img->h ? y0 + block : img->h;
    double sum = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++)
            sum += img->px[((size_t)y * img->w + x) * 3 + c];
    return sum / (255.0 * (x1 - x0) * (y1 - y0));
}

int metrics_compare_blocks(const struct rgb8 *ref, const struct rgb8 *img, int block, struct metrics *m,
                           struct err *e)
{
    if (ref->w != img->w || ref->h != img->h)
        return err_set(e, NULL, 0, 0, "image sizes differ: %dx%d against a %dx%d reference", img->w, img->h,
                       ref->w, ref->h);
    if (block < 1)
        return err_set(e, NULL, 0, 0, "block size must be >= 1, got %d", block);
    double se = 0, rel = 0;
    size_t n = 0;
    for (int y = 0; y < ref->h; y += block)
        for (int x = 0; x < ref->w; x += block)
            for (int c = 0; c < 3; c++) {
                double a = tile_mean(ref, x, y, block, c), b = tile_mean(img, x, y, block, c);
                double d = b - a;
                se += d * d;
                rel += d * d / (a * a + METRICS_REL_EPS);
                n++;
            }
    m->mse = n ? se / n : 0;
    m->rmse = sqrt(m->mse);
    m->relmse = n ? rel / n : 0;
    m->psnr = m->mse > 0 ? 10 * log10(1.0 / m->mse) : INFINITY;
    return 0;
}

int metrics_compare(const struct rgb8 *ref, const struct rgb8 *img, struct metrics *m, struct err *e)
{
    return metrics_compare_blocks(ref, img, 1, m, e);
}
