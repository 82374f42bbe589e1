/* metrics: per-channel error sums over two float images, optionally between the means of
   block x block tiles (a box filter that averages Monte Carlo noise away), and the trimmed
   relMSE that leaves the largest per-pixel terms out. */
#include "metrics.h"

#include <math.h>
#include <stdlib.h>

/* Mean of channel c over the tile at (x0, y0), clipped to the image, of m's pixels (all when m is
   NULL); NaN when the tile holds none of them. */
static double tile_mean(const struct rgbf *img, const struct img_mask *m, int x0, int y0, int block, int c)
{
    int x1 = x0 + block < img->w ? x0 + block : img->w, y1 = y0 + block < img->h ? y0 + block : img->h;
    double sum = 0, n = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++)
            if (mask_on(m, x, y))
                sum += img->px[((size_t)y * img->w + x) * 3 + c], n++;
    return n > 0 ? sum / n : NAN;
}

static void swap_d(double *a, double *b)
{
    double t = *a;
    *a = *b;
    *b = t;
}

/* Reorder t[0..n) so that t[0..k) holds its k smallest values (Hoare's selection, median of
   three pivots; deterministic). */
static void select_smallest(double *t, size_t n, size_t k)
{
    size_t lo = 0, hi = n; /* the k-th boundary lies in [lo, hi) */
    while (hi - lo > 2 && k > lo && k < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (t[mid] < t[lo])
            swap_d(&t[mid], &t[lo]);
        if (t[hi - 1] < t[lo])
            swap_d(&t[hi - 1], &t[lo]);
        if (t[hi - 1] < t[mid])
            swap_d(&t[hi - 1], &t[mid]);
        double pivot = t[mid];
        size_t i = lo, j = hi - 1;
        for (;;) { /* Hoare partition: [lo, j] <= pivot <= [j + 1, hi) */
            while (t[i] < pivot)
                i++;
            while (t[j] > pivot)
                j--;
            if (i >= j)
                break;
            swap_d(&t[i], &t[j]);
            i++;
            j--;
        }
        if (k <= j)
            hi = j + 1;
        else
            lo = j + 1;
    }
    if (hi - lo == 2 && t[lo + 1] < t[lo])
        swap_d(&t[lo], &t[lo + 1]);
}

int metrics_compare_f(const struct rgbf *ref, const struct rgbf *img, int block, struct metrics *m,
                      struct err *e)
{
    return metrics_compare_masked(ref, img, block, NULL, m, e);
}

int metrics_compare_masked(const struct rgbf *ref, const struct rgbf *img, int block,
                           const struct img_mask *mask, struct metrics *m, struct err *e)
{
    if (ref->w != img->w || ref->h != img->h)
        return err_set(e, NULL, 0, 0, "image sizes differ: %dx%d against a %dx%d reference", img->w, img->h,
                       ref->w, ref->h);
    if (block < 1)
        return err_set(e, NULL, 0, 0, "block size must be >= 1, got %d", block);
    if (mask && mask_check_size(mask, img->w, img->h, e) < 0)
        return -1;
    size_t n = (size_t)img->w * img->h * 3;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(ref->px[i]) || !isfinite(img->px[i]))
            return err_set(e, NULL, 0, 0, "%s has a non-finite value at pixel (%zu, %zu)",
                           isfinite(ref->px[i]) ? "the image" : "the reference", i / 3 % (size_t)img->w,
                           i / 3 / (size_t)img->w);
    size_t tiles_x = ((size_t)img->w + block - 1) / block,
           tiles = tiles_x * (((size_t)img->h + block - 1) / block);
    double *term = malloc(tiles * sizeof *term);
    if (!term)
        return err_set(e, NULL, 0, 0, "out of memory for %zu error terms", tiles);
    double se = 0, rel = 0;
    size_t k = 0;
    for (int y = 0; y < img->h; y += block)
        for (int x = 0; x < img->w; x += block) {
            if (mask && isnan(tile_mean(ref, mask, x, y, block, 0)))
                continue; /* no counted pixel in this tile */
            term[k] = 0;
            for (int c = 0; c < 3; c++) {
                double a = tile_mean(ref, mask, x, y, block, c), b = tile_mean(img, mask, x, y, block, c),
                       d = b - a;
                se += d * d;
                term[k] += d * d / (a * a + METRICS_REL_EPS);
            }
            rel += term[k];
            term[k++] /= 3;
        }
    tiles = k;
    m->mse = se / (3.0 * tiles);
    m->rmse = sqrt(m->mse);
    m->relmse = rel / (3.0 * tiles);
    size_t kept = tiles - (size_t)(tiles * METRICS_ROBUST_DROP);
    select_smallest(term, tiles, kept);
    double kept_sum = 0;
    for (size_t i = 0; i < kept; i++)
        kept_sum += term[i];
    m->relmse_robust = kept_sum / kept;
    m->psnr = m->mse > 0 ? 10 * log10(1.0 / m->mse) : INFINITY;
    free(term);
    return 0;
}

int metrics_display_compare(const struct rgb8 *ref, const struct rgb8 *img, struct metrics *m, struct err *e)
{
    return metrics_display_masked(ref, img, NULL, m, e);
}

int metrics_display_masked(const struct rgb8 *ref, const struct rgb8 *img, const struct img_mask *mask,
                           struct metrics *m, struct err *e)
{
    struct rgbf a = {0}, b = {0};
    int rc = image_f_from_rgb8(ref, &a, e) < 0 || image_f_from_rgb8(img, &b, e) < 0
                 ? -1
                 : metrics_compare_masked(&a, &b, 1, mask, m, e);
    image_f_free(&a);
    image_f_free(&b);
    return rc;
}
