/* render_material: what a surface's material gives the integrator besides its direction: the
   albedo (plain or a texture's lookup) and Schlick's reflectance of glass. Internal to
   common/render/, static. */
#ifndef RENDER_MATERIAL_H
#define RENDER_MATERIAL_H

#include "geom/scene.h"
#include "geom/shape.h"
#include "geom/texture.h"

static __attribute__((noinline, unused)) vec3 texture_albedo(const struct scene *sc, const struct material *m,
                                                             struct hit *h)
{
    const struct texture *t = &sc->textures[m->texture];
    if (texture_needs_uv(t))
        shape_uv(&sc->prims[h->prim], h);
    return texture_value(sc, t, h->u, h->v, h->p);
}

/* A plain material's albedo inline, a texture's lookup out of line (the call and its frame cost
   every untextured diffuse bounce ~20 instructions), on a copy of h, which the lookup fills with
   the uv: h itself then stays in the caller's registers. */
static inline __attribute__((always_inline)) vec3
surface_albedo(const struct scene *sc, const struct material *m, const struct hit *h)
{
    if (m->texture < 0)
        return m->albedo;
    struct hit copy = *h;
    return texture_albedo(sc, m, &copy);
}

static __attribute__((unused)) double reflectance(double cosine, double ref_idx)
{
    /* Schlick's approximation. */
    double r0 = (1 - ref_idx) / (1 + ref_idx);
    r0 *= r0;
    double x = 1 - cosine, x2 = x * x;
    return r0 + (1 - r0) * (x2 * x2 * x);
}

#endif
