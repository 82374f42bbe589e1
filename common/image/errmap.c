/* errmap: per-pixel relMSE terms on a fixed log scale, so maps of different images compare. */
#include "errmap.h"

#include <math.h>

#include "metrics.h"

/* Eight stops of an inferno-like ramp (dark purple to pale yellow), evenly spaced. */
static const uint8_t ramp[8][3] = {{0, 0, 4},     {40, 11, 84},   {101, 21, 110}, {159, 42, 99},
                                   {212, 72, 66}, {245, 125, 21}, {250, 193, 39}, {252, 255, 164}};

/* px = the ramp at u in [0, 1] (clamped). */
static void ramp_at(double u, uint8_t *px)
{
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    double f = u * 7;
    int i = f >= 7 ? 6 : (int)f;
    double t = f - i;
    for (int c = 0; c < 3; c++)
        px[c] = (uint8_t)lround(ramp[i][c] + t * (ramp[i + 1][c] - ramp[i][c]));
}

static void colour(double term, uint8_t *px)
{
    ramp_at(term > 0 ? (log10(term) - ERRMAP_LOG10_MIN) / (ERRMAP_LOG10_MAX - ERRMAP_LOG10_MIN) : 0, px);
    if (!(term > 0))
        px[0] = px[1] = px[2] = 0;
}

int errmap_make(const struct rgbf *ref, const struct rgbf *img, struct rgb8 *out, struct err *e)
{
    if (ref->w != img->w || ref->h != img->h)
        return err_set(e, NULL, 0, 0, "image sizes differ: %dx%d against a %dx%d reference", img->w, img->h,
                       ref->w, ref->h);
    if (image_alloc(out, ref->w, ref->h, e) < 0)
        return -1;
    for (size_t i = 0; i < (size_t)ref->w * ref->h; i++) {
        double term = 0;
        for (int c = 0; c < 3; c++) {
            double r = ref->px[3 * i + c], d = img->px[3 * i + c] - r;
            term += d * d / (r * r + METRICS_REL_EPS);
        }
        colour(term / 3, out->px + 3 * i);
    }
    return 0;
}

int errmap_flip(const float *flip, int w, int h, struct rgb8 *out, struct err *e)
{
    if (image_alloc(out, w, h, e) < 0)
        return -1;
    for (size_t i = 0; i < (size_t)w * h; i++)
        ramp_at(flip[i], out->px + 3 * i);
    return 0;
}

void errmap_outline(struct rgb8 *img, const struct img_mask *m)
{
    static const uint8_t rgb[3] = {ERRMAP_OUTLINE_RGB};
    for (int y = 0; y < img->h; y++)
        for (int x = 0; x < img->w; x++)
            if (!mask_on(m, x, y) &&
                ((x > 0 && mask_on(m, x - 1, y)) || (x + 1 < img->w && mask_on(m, x + 1, y)) ||
                 (y > 0 && mask_on(m, x, y - 1)) || (y + 1 < img->h && mask_on(m, x, y + 1))))
                for (int c = 0; c < 3; c++)
                    img->px[((size_t)y * img->w + x) * 3 + c] = rgb[c];
}

const char *errmap_scale_text(void)
{
    return "per-pixel relMSE term, mean over RGB of (v - r)^2 / (r^2 + 0.01); colour: log10 of it from -4 "
           "(black) to 2 (pale yellow), inferno-like ramp; 0 is black";
}
