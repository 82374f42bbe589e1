/* texture: solid checker and Perlin marble (RTOW "The Next Week", ch. 4-5) and image lookups
   by (u, v) with nearest-texel sampling (v = 0 at the bottom row, as the book). */
#include "texture.h"

static vec3 image_value(const struct rgb8 *img, double u, double v)
{
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    v = 1 - (v < 0 ? 0 : v > 1 ? 1 : v);
    int i = (int)(u * img->w), j = (int)(v * img->h);
    i = i >= img->w ? img->w - 1 : i;
    j = j >= img->h ? img->h - 1 : j;
    const uint8_t *px = img->px + ((size_t)j * (size_t)img->w + (size_t)i) * 3;
    const double s = 1.0 / 255;
    return v3(px[0] * s, px[1] * s, px[2] * s);
}

/* Whether sin(x) < 0, i.e. x / pi lies in an odd interval (k pi, (k + 1) pi): the checker needs
   only the sign of a product of sines, and libm's sin was a tenth of the checker scene's time.
   (x / pi may round across an integer within an ulp of k pi, where sin is below 1e-15 anyway.)
   Huge or non-finite arguments fall back to sin. */
static int sin_negative(double x)
{
    double q = x * (1 / PI);
    if (!(fabs(q) < 0x1.0p52))
        return sin(x) < 0;
    int64_t k = (int64_t)q; /* truncation; floor below */
    k -= (double)k > q;
    return (int)(k & 1);
}

vec3 texture_value(const struct scene *sc, const struct texture *t, double u, double v, vec3 p)
{
    switch (t->type) {
    case TEX_NOISE: { /* the marble of RTOW "The Next Week": grey 0.5 (1 + sin(scale z + 10 turb(p))) */
        double g = 0.5 * (1 + d_sin(t->scale * p.z + 10 * perlin_turb(sc->perlin, p, 7)));
        return v3(g, g, g);
    }
    case TEX_IMAGE:
        return image_value(&sc->images[t->image], u, v);
    default: {
        double x = t->scale * p.x, y = t->scale * p.y, z = t->scale * p.z;
        /* sin x sin y sin z < 0: an odd number of negative factors and none zero (sin of a
           non-zero double never is) */
        int zero = x == 0 || y == 0 || z == 0;
        return !zero && (sin_negative(x) ^ sin_negative(y) ^ sin_negative(z)) ? t->odd : t->even;
    }
    }
}

int texture_needs_uv(const struct texture *t)
{
    return t->type == TEX_IMAGE;
}
