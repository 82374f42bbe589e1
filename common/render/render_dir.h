/* render_dir: the scattered directions: the metal's fuzz ball, the diffuse cosine lobe and the
   medium's uniform sphere, each from the path's rng or from two given uniforms. Internal to
   common/render/; static, so render.c and render_lanes.c each keep their own inlined copies. */
#ifndef RENDER_DIR_H
#define RENDER_DIR_H

#include "base/rng.h"
#include "base/vec3.h"

static __attribute__((unused)) vec3 random_in_unit_sphere(struct rng *r)
{
    for (;;) {
        /* one draw a declarator: a call's arguments have no order in C (gcc took them last
           first, clang first first); z, y, x keeps the images gcc made */
        double z = 2 * rng_uniform32(r) - 1, y = 2 * rng_uniform32(r) - 1, x = 2 * rng_uniform32(r) - 1;
        vec3 p = v3(x, y, z);
        if (v3_len2(p) < 1)
            return p;
    }
}

/* Cosine-weighted direction about n (Malley's method) from two uniforms: u2 the radius squared,
   a the angle in turns. */
static inline __attribute__((always_inline, unused)) vec3 cosine_direction_uv(const onb *frame, double u2,
                                                                              double a)
{
    double s = sqrt(u2), sin_phi, cos_phi;
    v3_sincos_turn(a, &sin_phi, &cos_phi);
    return onb_local(frame, v3(cos_phi * s, sin_phi * s, sqrt(1 - u2)));
}

/* cosine_direction_uv from r. Always inline: with next-event estimation's call beside the mixture's GCC kept
   it out of line, +2% of cornell-book3's instructions. */
static inline __attribute__((always_inline, unused)) vec3 cosine_direction(const onb *frame, struct rng *r)
{
    double u2 = rng_uniform32(r);
    return cosine_direction_uv(frame, u2, rng_uniform32(r));
}

/* A uniform direction from two uniforms (z from u, the angle in turns from a). */
static inline __attribute__((always_inline, unused)) vec3 uniform_sphere_direction_uv(double u, double a)
{
    double z = 1 - 2 * u, s = sqrt(d_max(0, 1 - z * z)), sin_phi, cos_phi;
    v3_sincos_turn(a, &sin_phi, &cos_phi);
    return v3(cos_phi * s, sin_phi * s, z);
}

/* A uniform direction: inline where trace scatters in a medium (path_scatter's media_inline),
   a call elsewhere (GCC's choice; inline in the lanes it cost cornell-book3 7 instructions). */
static inline __attribute__((always_inline, unused)) vec3 uniform_sphere_direction_inline(struct rng *r)
{
    double u = rng_uniform32(r);
    return uniform_sphere_direction_uv(u, rng_uniform32(r));
}

static __attribute__((unused)) vec3 uniform_sphere_direction(struct rng *r)
{
    return uniform_sphere_direction_inline(r);
}

#endif
