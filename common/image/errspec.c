/* errspec: the luminance error's spectrum by a separable DFT of a centred crop (errspec.h). */
#include "errspec.h"

#include <math.h>
#include <stdlib.h>

/* The periodogram |DFT|^2 of the mean-free luminance error of img against ref on the centred crop,
   into power[ky * w + kx] (w x h the crop's, at most ERRSPEC_MAX_SIDE a side). */
static int periodogram(const struct rgbf *ref, const struct rgbf *img, double *power, int *cw, int *ch,
                       struct err *e)
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
    *cw = w, *ch = h;
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
    /* then columns */
    for (int k = 0; k < h; k++)
        tw[2 * k] = cos(2 * M_PI * k / h), tw[2 * k + 1] = -sin(2 * M_PI * k / h);
    for (int kx = 0; kx < w; kx++)
        for (int ky = 0; ky < h; ky++) {
            double sr = 0, si = 0;
            for (int y = 0; y < h; y++) {
                const int t = (int)(((long)ky * y) % h);
                sr += re[y * w + kx] * tw[2 * t] - im[y * w + kx] * tw[2 * t + 1];
                si += re[y * w + kx] * tw[2 * t + 1] + im[y * w + kx] * tw[2 * t];
            }
            power[ky * w + kx] = sr * sr + si * si;
        }
    free(err_img), free(re), free(im), free(tw);
    return 0;
}

/* Frequency (kx, ky) of a w x h DFT in units of Nyquist, each axis in [-1, 1]. */
static void freq(int kx, int ky, int w, int h, double *fx, double *fy)
{
    *fx = (kx <= w / 2 ? kx : kx - w) / (w / 2.0), *fy = (ky <= h / 2 ? ky : ky - h) / (h / 2.0);
}

int errspec_lowfreq(const struct rgbf *ref, const struct rgbf *img, double *lowfreq, struct err *e)
{
    double *power = malloc((size_t)ERRSPEC_MAX_SIDE * ERRSPEC_MAX_SIDE * sizeof *power);
    int w, h;
    if (!power)
        return err_set(e, NULL, 0, 0, "out of memory for an error spectrum");
    if (periodogram(ref, img, power, &w, &h, e) < 0) {
        free(power);
        return -1;
    }
    double low = 0, total = 0;
    long n_low = 0, n_all = 0;
    for (int kx = 0; kx < w; kx++)
        for (int ky = 0; ky < h; ky++) {
            if (kx == 0 && ky == 0)
                continue;
            double fx, fy;
            freq(kx, ky, w, h, &fx, &fy);
            const double p = power[ky * w + kx];
            const int in_low = fx * fx + fy * fy <= ERRSPEC_LOW_RADIUS * ERRSPEC_LOW_RADIUS;
            total += p;
            n_all++;
            if (in_low)
                low += p, n_low++;
        }
    *lowfreq = n_low > 0 && total > 0 ? (low / total) / ((double)n_low / (double)n_all) : NAN;
    free(power);
    return 0;
}

int errspec_power_add(const struct rgbf *ref, const struct rgbf *img, double *acc, int *w, int *h,
                      struct err *e)
{
    double *power = malloc((size_t)ERRSPEC_MAX_SIDE * ERRSPEC_MAX_SIDE * sizeof *power);
    if (!power)
        return err_set(e, NULL, 0, 0, "out of memory for an error spectrum");
    int rc = periodogram(ref, img, power, w, h, e);
    for (int i = 0; rc == 0 && i < *w * *h; i++)
        acc[i] += power[i];
    free(power);
    return rc;
}

/* The ring of (kx, ky): floor(radius x ERRSPEC_RINGS), radius in units of Nyquist; -1 for DC and
   beyond Nyquist (the corners). Its orientation sector (0: near the x axis, 1: 45 degrees, 2: the
   y axis, 3: 135 degrees) into sector. */
static int ring_of(int kx, int ky, int w, int h, int *sector)
{
    double fx, fy;
    freq(kx, ky, w, h, &fx, &fy);
    double r = sqrt(fx * fx + fy * fy), a = atan2(fy, fx);
    if (a < 0)
        a += M_PI;
    *sector = (int)floor(a / (M_PI / 4) + 0.5) % 4;
    return (kx == 0 && ky == 0) || r >= 1 ? -1 : (int)(r * ERRSPEC_RINGS);
}

/* Chernoff's bound on P(G > t) for G the mean of n unit exponentials: exp(-n (t - 1 - ln t)). */
static double exp_mean_tail(double t, int n)
{
    return t <= 1 ? 1 : exp(-n * (t - 1 - log(t)));
}

void errspec_look_of(const double *acc, int w, int h, int n, struct errspec_look *out)
{
    double sum[ERRSPEC_RINGS] = {0}, sect[4] = {0}, total = 0;
    long cnt[ERRSPEC_RINGS] = {0}, sect_n[4] = {0}, all = 0;
    int sector;
    for (int ky = 0; ky < h; ky++)
        for (int kx = 0; kx < w; kx++) {
            int r = ring_of(kx, ky, w, h, &sector);
            if (r >= 0)
                sum[r] += acc[ky * w + kx], cnt[r]++, total += acc[ky * w + kx], all++;
        }
    double mean = all && total > 0 ? total / all : NAN;
    for (int r = 0; r < ERRSPEC_RINGS; r++)
        out->ring[r] = cnt[r] && mean > 0 ? sum[r] / cnt[r] / mean : NAN;
    /* the largest bin over its ring's mean, in rings of ERRSPEC_RING_MIN bins or more; the bins come
       in conjugate pairs (a real image), so half of them are independent */
    double peak = 0;
    long tested = 0;
    for (int ky = 0; ky < h; ky++)
        for (int kx = 0; kx < w; kx++) {
            int r = ring_of(kx, ky, w, h, &sector);
            if (r < 0 || cnt[r] < ERRSPEC_RING_MIN || !(sum[r] > 0))
                continue;
            double q = acc[ky * w + kx] / (sum[r] / cnt[r]);
            tested++;
            peak = fmax(peak, q);
            if (r >= ERRSPEC_RINGS / 4) /* orientation from the upper three quarters of the rings */
                sect[sector] += q, sect_n[sector]++;
        }
    out->peak = tested ? peak : NAN;
    out->peak_p = tested ? fmin(1, (double)tested / 2 * exp_mean_tail(peak, n)) : NAN;
    double lo = INFINITY, hi = 0;
    for (int i = 0; i < 4; i++)
        if (sect_n[i])
            lo = fmin(lo, sect[i] / sect_n[i]), hi = fmax(hi, sect[i] / sect_n[i]);
    out->anisotropy = lo > 0 && isfinite(lo) ? hi / lo : NAN;
}
