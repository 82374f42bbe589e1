/* render_internal: the render context that render.c and render_ctx.c share. Internal to
   common/. */
#ifndef RENDER_INTERNAL_H
#define RENDER_INTERNAL_H

#include "geom/packet.h"
#include "render.h"
#include "base/rng.h"
#include "sample/padding.h"
#include "sample/sobol.h"

/* A light's current point set within the pixel, taken in a random order, then redrawn: the
   points themselves (fresh poisson), the indices of a pool set's points, shifted when taken
   (pooled poisson), the indices of a sobol set's points, made when taken, or the cells whose
   points are made when taken (the others). */
struct light_points {
    struct pt2 *pts;
    uint32_t *cells;
    const struct pool_point *pool; /* pooled: the set and its shift */
    double ox, oy, cos_oy, sin_oy;
    struct sobol_seeds sobol; /* sobol: the set's seeds */
    size_t n, next;
    int uses_points; /* shape_light_uses_points of the light, looked up once */
};

/* sampler_dims: all: the sets' slots. Two for the camera (lens point; shutter time in x), then
   per bounce the scatter direction, the light point and (the mixture's or glass's coin in x,
   the light's choice in y). */
#define DIMS_CAMERA 2
#define DIMS_PER_BOUNCE 3
enum { DIM_DIR, DIM_LIGHT, DIM_CHOICE };

struct render_ctx {
    const struct scene *sc;
    const struct camera *cam;
    struct render_settings rs;
    struct sampler *pixel, *light;
    enum sampler_kind light_kind;
    struct sampler_grid light_grid; /* the light sampler's grid (uniform, jitter, random) */
    struct pt2 *pixel_pts;
    struct light_points *lp;               /* one per scene light */
    uint32_t *identity;                    /* 0, 1, 2, ...: a fresh shuffle's start, copied */
    const struct material **prim_material; /* each prim's material: one load after a hit */
    struct rng light_rng;
    struct render_stats *st;
    int timed; /* the current pixel is timed (sampler_timed): its light draws add to timed_draw_ns */
    struct packet_scene *packet; /* NULL, or four paths at once through packet_hit */
    /* sampler_dims: all: the pixel sampler's padded sets (sample/padding.h), DIMS_CAMERA +
       DIMS_PER_BOUNCE * dims_bounces slots; bounces past dims_bounces draw from the path's rng */
    struct padding pad;
    int dims_bounces;
};

/* render_pixel's samples (n of them, the pixel's points in ctx->pixel_pts) four paths at a
   time through packet_hit (render_lanes.c; ctx->packet set), each sample's rng started from the
   pixel's path stream *base; mix: the scene's lights are sampled by the mixture, nee: by
   next-event estimation; dims: sampler_dims: all; last: max_depth - 1. Their finite estimates
   go into sum (add_estimate), the count of the others into *nonfinite, their segments into
   *rays. */
void render_pixel_packet(struct render_ctx *ctx, int x, int y, size_t n, const struct rng *base, int mix,
                         int nee, int dims, int last, double sum[3], uint64_t *nonfinite, uint64_t *rays);

#endif
