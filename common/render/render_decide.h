/* render_decide: where a vertex's decisions come from under sampler_dims: all (the pixel's padded
   sets while the bounce has them, else the path's rng), and the camera ray and fuzz ball drawn
   from them. Internal to common/render/, static. */
#ifndef RENDER_DECIDE_H
#define RENDER_DECIDE_H

#include "render_dir.h"
#include "render_internal.h"

/* Decision k (DIM_DIR, DIM_LIGHT, DIM_CHOICE, DIM_ROULETTE) of the vertex at->depth: two uniforms. */
static inline __attribute__((always_inline)) struct pt2 path_decide(struct render_ctx *ctx, struct rng *rng,
                                                                    struct path_at at, int k)
{
    if (at.depth < ctx->dims_bounces) {
        ctx->padded_points++;
        return padding_point(&ctx->pad, render_dims_slot(ctx, at.depth, k), at.sample);
    }
    struct pt2 p;
    p.x = rng_uniform32(rng);
    p.y = rng_uniform32(rng);
    return p;
}

/* A uniform point in the unit ball from the vertex's sets (sampler_dims: all; what
   random_in_unit_sphere draws by rejection): its direction from the direction's point, its
   radius cbrt(u) from the choice's x (a metal vertex makes no other use of either). */
static __attribute__((unused)) vec3 in_unit_ball(struct render_ctx *ctx, struct rng *rng, struct path_at at)
{
    const struct pt2 d = path_decide(ctx, rng, at, DIM_DIR), c = path_decide(ctx, rng, at, DIM_CHOICE);
    return v3_scale(uniform_sphere_direction_uv(d.x, d.y), cbrt(c.x));
}

/* camera_ray under sampler_dims: all: the lens point and the shutter time of sample s from the
   pixel's sets, each drawn only where it is used: the lens point with a lens, the time with a
   shutter interval and a scene whose hits depend on it (else the shutter's opening: the same
   hits, and the other sets' points do not depend on whether this one is read). */
static inline __attribute__((always_inline)) ray render_camera_ray_dims(struct render_ctx *ctx, double u,
                                                                        double v, uint32_t s)
{
    const struct camera *cam = ctx->cam;
    struct pt2 lens = {0, 0}, time = {0, 0};
    if (cam->lens_radius > 0) {
        ctx->padded_points++;
        lens = padding_point(&ctx->pad, 0, s);
    }
    if (cam->time0 != cam->time1 && ctx->time_matters) {
        ctx->padded_points++;
        time = padding_point(&ctx->pad, 1, s);
    }
    return camera_ray_at(cam, u, v, lens.x, lens.y, time.x);
}

#endif
