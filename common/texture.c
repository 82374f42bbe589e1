/* texture: solid checker and Perlin marble (RTOW "The Next Week", ch. 4-5) and image lookups
   by (u, v) with nearest-texel sampling (v = 0 at the bottom row, as the book). */
#include "texture.h"

vec3 texture_marble(const struct perlin *pn, double scale, vec3 p)
{
    double g = 0.5 * (1 + sin(scale * p.z + 10 * perlin_turb(pn, p, 7)));
    return v3(g, g, g);
}

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

vec3 texture_value(const struct scene *sc, const struct texture *t, double u, double v, vec3 p)
{
    switch (t->type) {
    case TEX_NOISE:
        return texture_marble(sc->perlin, t->scale, p);
    case TEX_IMAGE:
        return image_value(&sc->images[t->image], u, v);
    default: {
        double s = sin(t->scale * p.x) * sin(t->scale * p.y) * sin(t->scale * p.z);
        return s < 0 ? t->odd : t->even;
    }
    }
}

int texture_needs_uv(const struct texture *t)
{
    return t->type == TEX_IMAGE;
}
