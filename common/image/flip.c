/* flip: LDR-FLIP and HDR-FLIP (flip.h names the papers). The colour pipeline: linear RGB to the
   opponent space YCxCz, each channel filtered by its contrast sensitivity function (sums of
   Gaussians) at FLIP_PPD, back to linear RGB clamped to the unit cube, to CIELAB with the Hunt
   adjustment (a and b scaled by L / 100), the HyAB distance |dL| + |d(a, b)|, raised to 0.7 and
   mapped to [0, 1] against the distance from green to blue. The feature pipeline: edges (first
   derivative of a Gaussian) and points (second derivative) of the luminance, their largest change.
   Per pixel: colour ^ (1 - feature). All filters are separable and clamp at the image's edges. */
#include "flip.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FLIP_PI 3.14159265358979323846
#define QC 0.7 /* colour exponent */
#define PC 0.4 /* errors up to PC * cmax take the first PT of the range */
#define PT 0.95
#define EDGE_W 0.082  /* peak-to-trough width of the edge detector, in degrees */
#define RADIUS_MAX 24 /* room for the filters' radii at FLIP_PPD (10 and 9) */
#define TONE_T 0.85   /* HDR-FLIP: the tone-mapped value the brightest and the median pixel reach */

/* The filters at FLIP_PPD and the colour constants, made once per call. */
struct flip_ctx {
    double rgb2xyz[9], xyz2rgb[9], white[3], cmax; /* row-major */
    int r_csf, n_gauss[3];
    float csf[3][2][2 * RADIUS_MAX + 1]; /* channel, Gaussian: 1D taps, the 2D weight in csf_y */
    float csf_y[3][2][2 * RADIUS_MAX + 1];
    int r_feat;
    float gauss[2 * RADIUS_MAX + 1], edge[2 * RADIUS_MAX + 1], point[2 * RADIUS_MAX + 1];
    int w, h;
    float *ycc[3], *tmp, *tmp2, *tmp3, *lin; /* work planes (lin: w*h*3) */
    float *pad;                              /* one row with RADIUS_MAX clamped pixels each side */
    float *lab[2][3], *edges[2], *points[2]; /* reference, test */
    float *acc;
};

static inline double lab_f(double t)
{
    const double d = 6.0 / 29;
    return t > d * d * d ? cbrtf((float)t) : t / (3 * d * d) + 4.0 / 29;
}

/* out = m in, m a row-major 3x3 matrix. */
static void mat_apply(const double *m, const double in[3], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = m[3 * r] * in[0] + m[3 * r + 1] * in[1] + m[3 * r + 2] * in[2];
}

/* Hunt-adjusted L*a*b* of linear RGB rgb. */
static void hunt_lab(const struct flip_ctx *k, const double rgb[3], double lab[3])
{
    double xyz[3];
    mat_apply(k->rgb2xyz, rgb, xyz);
    double fx = lab_f(xyz[0] / k->white[0]), fy = lab_f(xyz[1] / k->white[1]),
           fz = lab_f(xyz[2] / k->white[2]);
    lab[0] = 116 * fy - 16;
    lab[1] = 0.01 * lab[0] * 500 * (fx - fy);
    lab[2] = 0.01 * lab[0] * 200 * (fy - fz);
}

static double hyab(const double a[3], const double b[3])
{
    return fabs(a[0] - b[0]) + hypot(a[1] - b[1], a[2] - b[2]);
}

/* 1D taps w[-r..r] scaled so their positive ones sum to 1 and their negative ones to -1. */
static void normalise_signed(float *w, int r)
{
    double pos = 0, neg = 0;
    for (int i = 0; i <= 2 * r; i++)
        pos += w[i] > 0 ? w[i] : 0, neg -= w[i] < 0 ? w[i] : 0;
    for (int i = 0; i <= 2 * r; i++)
        w[i] = (float)(w[i] > 0 ? w[i] / pos : w[i] / neg);
}

static void ctx_filters(struct flip_ctx *k, double ppd)
{
    /* The contrast sensitivity functions' Gaussians (a, b) per channel: achromatic, red-green,
       blue-yellow (HPG 2020, section 4.1); a = 0: none. */
    static const double ab[3][2][2] = {
        {{1, 0.0047}, {0, 1e-5}}, {{1, 0.0053}, {0, 1e-5}}, {{34.1, 0.04}, {13.5, 0.025}}};
    double bmax = 0.04, dx = 1 / ppd;
    k->r_csf = (int)ceil(3 * sqrt(bmax / (2 * FLIP_PI * FLIP_PI)) * ppd);
    for (int c = 0; c < 3; c++) {
        double sum2d = 0, sums[2] = {0, 0}, amp[2];
        k->n_gauss[c] = 0;
        for (int g = 0; g < 2 && ab[c][g][0] != 0; g++, k->n_gauss[c]++) {
            amp[g] = ab[c][g][0] * sqrt(FLIP_PI / ab[c][g][1]);
            for (int i = -k->r_csf; i <= k->r_csf; i++) {
                double v = exp(-FLIP_PI * FLIP_PI * (i * dx) * (i * dx) / ab[c][g][1]);
                k->csf[c][g][i + k->r_csf] = (float)v;
                sums[g] += v;
            }
            sum2d += amp[g] * sums[g] * sums[g]; /* the 2D filter's sum, to normalise it to 1 */
        }
        for (int g = 0; g < k->n_gauss[c]; g++)
            for (int i = 0; i <= 2 * k->r_csf; i++)
                k->csf_y[c][g][i] = (float)(k->csf[c][g][i] * amp[g] / sum2d);
    }
    double sd = 0.5 * EDGE_W * ppd, gsum = 0;
    k->r_feat = (int)ceil(3 * sd);
    for (int i = -k->r_feat; i <= k->r_feat; i++) {
        double g = exp(-(double)i * i / (2 * sd * sd));
        k->gauss[i + k->r_feat] = (float)g;
        k->edge[i + k->r_feat] = (float)(-i * g);
        k->point[i + k->r_feat] = (float)(((double)i * i / (sd * sd) - 1) * g);
        gsum += g;
    }
    for (int i = 0; i <= 2 * k->r_feat; i++)
        k->gauss[i] = (float)(k->gauss[i] / gsum);
    /* the 2D detector x * gauss(y) keeps its signs' sums at +-1 when x's are and gauss sums to 1 */
    normalise_signed(k->edge, k->r_feat);
    normalise_signed(k->point, k->r_feat);
}

static void ctx_colour(struct flip_ctx *k)
{
    /* linear sRGB (D65) to XYZ */
    static const double m[3][3] = {{10135552.0 / 24577794, 8788810.0 / 24577794, 4435075.0 / 24577794},
                                   {2613072.0 / 12288897, 8788810.0 / 12288897, 887015.0 / 12288897},
                                   {1425312.0 / 73733382, 8788810.0 / 73733382, 70074185.0 / 73733382}};
    memcpy(k->rgb2xyz, m, sizeof m);
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++) /* the adjugate's (r, c): cofactor (c, r) */
            k->xyz2rgb[3 * r + c] = (m[(c + 1) % 3][(r + 1) % 3] * m[(c + 2) % 3][(r + 2) % 3] -
                                     m[(c + 1) % 3][(r + 2) % 3] * m[(c + 2) % 3][(r + 1) % 3]) /
                                    det;
        k->white[r] = m[r][0] + m[r][1] + m[r][2];
    }
    double green[3] = {0, 1, 0}, blue[3] = {0, 0, 1}, lg[3], lb[3];
    hunt_lab(k, green, lg);
    hunt_lab(k, blue, lb);
    k->cmax = pow(hyab(lg, lb), QC);
}

static int ctx_make(struct flip_ctx *k, int w, int h, struct err *e)
{
    memset(k, 0, sizeof *k);
    ctx_filters(k, FLIP_PPD);
    ctx_colour(k);
    k->w = w, k->h = h;
    size_t n = (size_t)w * h;
    float *all = malloc((24 * n + (size_t)w + 2 * RADIUS_MAX) * sizeof *all);
    if (!all)
        return err_set(e, NULL, 0, 0, "out of memory for FLIP's planes of a %dx%d image", w, h);
    float **planes[] = {&k->ycc[0],    &k->ycc[1],    &k->ycc[2],    &k->tmp,       &k->tmp2,
                        &k->tmp3,      &k->acc,       &k->lab[0][0], &k->lab[0][1], &k->lab[0][2],
                        &k->lab[1][0], &k->lab[1][1], &k->lab[1][2], &k->edges[0],  &k->edges[1],
                        &k->points[0], &k->points[1], &k->lin};
    for (size_t i = 0; i < sizeof planes / sizeof *planes; i++)
        *planes[i] = all + i * n; /* lin last: three planes' room */
    k->pad = all + 24 * n;
    return 0;
}

/* Four floats in one vector register (GCC and clang): each lane does the scalar loop's operations
   in its order, so the sums are the same bit for bit. */
typedef float flip_f4 __attribute__((vector_size(16)));

/* acc[x] += c * src[x] for x < n. */
static void axpy(float *acc, float c, const float *src, int n)
{
    int x = 0;
    flip_f4 cv = {c, c, c, c};
    for (; x + 4 <= n; x += 4) {
        flip_f4 a, b;
        memcpy(&a, acc + x, sizeof a);
        memcpy(&b, src + x, sizeof b);
        a += cv * b;
        memcpy(acc + x, &a, sizeof a);
    }
    for (; x < n; x++)
        acc[x] += c * src[x];
}

/* out = in filtered along rows by kx then along columns by ky (radius r), edges clamped (a row is
   copied with its clamped ends into k->pad first, so the inner loops run over x unchecked). Each
   output sums its taps in one order, whatever the loops' shape. */
static void sep_filter(const struct flip_ctx *k, const float *in, float *out, const float *kx,
                       const float *ky, int r)
{
    int w = k->w, h = k->h;
    for (int y = 0; y < h; y++) {
        const float *row = in + (size_t)y * w;
        float *t = k->tmp + (size_t)y * w;
        for (int x = -r; x < w + r; x++)
            k->pad[x + r] = row[x < 0 ? 0 : x >= w ? w - 1 : x];
        memset(t, 0, (size_t)w * sizeof *t);
        for (int i = 0; i <= 2 * r; i++)
            axpy(t, kx[i], k->pad + i, w);
    }
    for (int y = 0; y < h; y++) {
        float *o = out + (size_t)y * w;
        memset(o, 0, (size_t)w * sizeof *o);
        for (int i = -r; i <= r; i++) {
            int yy = y + i < 0 ? 0 : y + i >= h ? h - 1 : y + i;
            axpy(o, ky[i + r], k->tmp + (size_t)yy * w, w);
        }
    }
}

/* The length of (f along x, f along y) of plane in for the detector taps d into out. */
static void features(struct flip_ctx *k, const float *in, const float *d, float *out)
{
    sep_filter(k, in, k->tmp2, d, k->gauss, k->r_feat);
    sep_filter(k, in, out, k->gauss, d, k->r_feat);
    for (size_t i = 0; i < (size_t)k->w * k->h; i++)
        out[i] = hypotf(k->tmp2[i], out[i]);
}

/* Image `which` (0 reference, 1 test) from k->lin (linear RGB in [0, 1], interleaved): its
   filtered Hunt-adjusted L*a*b* planes, edge and point strengths. */
static void prepare(struct flip_ctx *k, int which)
{
    size_t n = (size_t)k->w * k->h;
    for (size_t i = 0; i < n; i++) {
        double rgb[3] = {k->lin[3 * i], k->lin[3 * i + 1], k->lin[3 * i + 2]}, xyz[3];
        mat_apply(k->rgb2xyz, rgb, xyz);
        double x = xyz[0] / k->white[0], y = xyz[1] / k->white[1], z = xyz[2] / k->white[2];
        k->ycc[0][i] = (float)(116 * y - 16);
        k->ycc[1][i] = (float)(500 * (x - y));
        k->ycc[2][i] = (float)(200 * (y - z));
        k->tmp3[i] = (float)y; /* the normalised achromatic value (Y + 16) / 116 */
    }
    features(k, k->tmp3, k->edge, k->edges[which]);
    features(k, k->tmp3, k->point, k->points[which]);
    for (int c = 0; c < 3; c++) {
        float *out = k->lab[which][c];
        sep_filter(k, k->ycc[c], out, k->csf[c][0], k->csf_y[c][0], k->r_csf);
        if (k->n_gauss[c] > 1) {
            sep_filter(k, k->ycc[c], k->tmp2, k->csf[c][1], k->csf_y[c][1], k->r_csf);
            for (size_t i = 0; i < n; i++)
                out[i] += k->tmp2[i];
        }
    }
    for (size_t i = 0; i < n; i++) {
        double y = (k->lab[which][0][i] + 16.0) / 116, xyz[3], rgb[3], lab[3];
        xyz[0] = (y + k->lab[which][1][i] / 500.0) * k->white[0];
        xyz[1] = y * k->white[1];
        xyz[2] = (y - k->lab[which][2][i] / 200.0) * k->white[2];
        mat_apply(k->xyz2rgb, xyz, rgb);
        for (int c = 0; c < 3; c++)
            rgb[c] = rgb[c] < 0 ? 0 : rgb[c] > 1 ? 1 : rgb[c];
        hunt_lab(k, rgb, lab);
        for (int c = 0; c < 3; c++)
            k->lab[which][c][i] = (float)lab[c];
    }
}

/* LDR-FLIP of the prepared pair, per pixel, into out (its maximum with out's values when max). */
static void combine(struct flip_ctx *k, float *out, int max)
{
    double pccmax = PC * k->cmax;
    for (size_t i = 0; i < (size_t)k->w * k->h; i++) {
        double a[3] = {k->lab[0][0][i], k->lab[0][1][i], k->lab[0][2][i]},
               b[3] = {k->lab[1][0][i], k->lab[1][1][i], k->lab[1][2][i]};
        double hc = powf((float)hyab(a, b), (float)QC);
        double dc = hc < pccmax ? PT / pccmax * hc : PT + (hc - pccmax) / (k->cmax - pccmax) * (1 - PT);
        double de = fabs(k->edges[0][i] - k->edges[1][i]), dp = fabs(k->points[0][i] - k->points[1][i]);
        double df = sqrt((de > dp ? de : dp) / sqrt(2.0)); /* to the feature exponent 0.5 */
        float v = powf((float)dc, (float)(1 - df));
        out[i] = max && out[i] > v ? out[i] : v;
    }
}

static int check_pair(const struct rgbf *ref, const struct rgbf *img, const struct img_mask *m, struct err *e)
{
    if (ref->w != img->w || ref->h != img->h)
        return err_set(e, NULL, 0, 0, "image sizes differ: %dx%d against a %dx%d reference", img->w, img->h,
                       ref->w, ref->h);
    if (m && mask_check_size(m, ref->w, ref->h, e) < 0)
        return -1;
    for (size_t i = 0; i < (size_t)ref->w * ref->h * 3; i++)
        if (!isfinite(ref->px[i]) || !isfinite(img->px[i]))
            return err_set(e, NULL, 0, 0, "FLIP: %s has a non-finite value at pixel (%zu, %zu)",
                           isfinite(ref->px[i]) ? "the image" : "the reference", i / 3 % (size_t)ref->w,
                           i / 3 / (size_t)ref->w);
    return 0;
}

static void finish(const struct flip_ctx *k, const struct img_mask *m, float *map, struct flip_result *out)
{
    double sum = 0;
    size_t count = 0;
    for (int y = 0; y < k->h; y++)
        for (int x = 0; x < k->w; x++)
            if (mask_on(m, x, y))
                sum += k->acc[(size_t)y * k->w + x], count++;
    out->mean = count ? sum / count : 0;
    if (map)
        memcpy(map, k->acc, (size_t)k->w * k->h * sizeof *map);
}

static inline double srgb_decode(double v)
{
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    return v > 0.04045 ? pow((v + 0.055) / 1.055, 2.4) : v / 12.92;
}

/* ACES filmic curve (Narkowicz 2016) as a ratio of quadratics, its 0.6 pre-exposure folded in. */
static const double aces[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};

static inline double tone_map(double v, double scale)
{
    double x = (v > 0 ? v : 0) * scale;
    double y = (aces[0] * x * x + aces[1] * x + aces[2]) / (aces[3] * x * x + aces[4] * x + aces[5]);
    return isfinite(y) ? (y < 0 ? 0 : y > 1 ? 1 : y) : 1;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* HDR-FLIP's exposures from ref's luminance over m's pixels (RTG II, section 19.5.2): start puts
   the brightest at TONE_T after the tone mapper, stop the median (numpy's: the mean of the middle
   two); a median of 0 takes the dimmest lit pixel instead. */
static int exposures(const struct rgbf *ref, const struct img_mask *m, struct flip_result *out, struct err *e)
{
    size_t n = 0, cap = (size_t)ref->w * ref->h;
    double *lum = malloc(cap * sizeof *lum), hi = 0, lo_pos = INFINITY;
    if (!lum)
        return err_set(e, NULL, 0, 0, "out of memory for FLIP's exposures");
    for (int y = 0; y < ref->h; y++)
        for (int x = 0; x < ref->w; x++)
            if (mask_on(m, x, y)) {
                const float *p = ref->px + ((size_t)y * ref->w + x) * 3;
                double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
                lum[n++] = l;
                hi = l > hi ? l : hi;
                lo_pos = l > 0 && l < lo_pos ? l : lo_pos;
            }
    qsort(lum, n, sizeof *lum, cmp_double);
    double median = n % 2 ? lum[n / 2] : 0.5 * (lum[n / 2 - 1] + lum[n / 2]);
    free(lum);
    double c0 = (aces[1] - aces[4] * TONE_T) / (aces[0] - aces[3] * TONE_T),
           c1 = (aces[2] - aces[5] * TONE_T) / (aces[0] - aces[3] * TONE_T);
    double x_t = -0.5 * c0 + sqrt(0.25 * c0 * c0 - c1); /* tone_map(x_t) = TONE_T */
    out->start_exposure = out->stop_exposure = 0;
    if (hi > 0) {
        out->start_exposure = log2(x_t / hi);
        out->stop_exposure = log2(x_t / (median > 0 ? median : lo_pos));
    }
    double span = ceil(out->stop_exposure - out->start_exposure);
    out->n_exposures = span < 2 ? 2 : span > FLIP_MAX_EXPOSURES ? FLIP_MAX_EXPOSURES : (int)span;
    return 0;
}

/* LDR-FLIP (hdr 0), or HDR-FLIP (1): LDR-FLIP of each exposure's tone-mapped pair, the per-pixel
   maximum. */
static int flip_run(const struct rgbf *ref, const struct rgbf *img, const struct img_mask *m, float *map,
                    struct flip_result *out, struct err *e, int hdr)
{
    struct flip_ctx k;
    *out = (struct flip_result){0, hdr, 0, 0, 0};
    if (check_pair(ref, img, m, e) < 0 || (hdr && exposures(ref, m, out, e) < 0) ||
        ctx_make(&k, ref->w, ref->h, e) < 0)
        return -1;
    const int n = hdr ? out->n_exposures : 1;
    const double step = hdr ? (out->stop_exposure - out->start_exposure) / (n - 1) : 0;
    const struct rgbf *pair[2] = {ref, img};
    for (int x = 0; x < n; x++) {
        const double scale = exp2(out->start_exposure + x * step);
        for (int which = 0; which < 2; which++) {
            const float *px = pair[which]->px;
            for (size_t i = 0; i < (size_t)ref->w * ref->h * 3; i++)
                k.lin[i] = (float)(hdr ? tone_map(px[i], scale) : srgb_decode(px[i]));
            prepare(&k, which);
        }
        combine(&k, k.acc, x > 0);
    }
    finish(&k, m, map, out);
    free(k.ycc[0]); /* every plane's block (ctx_make) */
    return 0;
}

int flip_ldr(const struct rgbf *ref, const struct rgbf *img, const struct img_mask *m, float *map,
             struct flip_result *out, struct err *e)
{
    return flip_run(ref, img, m, map, out, e, 0);
}

int flip_hdr(const struct rgbf *ref, const struct rgbf *img, const struct img_mask *m, float *map,
             struct flip_result *out, struct err *e)
{
    return flip_run(ref, img, m, map, out, e, 1);
}
