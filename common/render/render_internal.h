/* render_internal: the render context that render.c and render_ctx.c share. Internal to
   common/. */
#ifndef RENDER_INTERNAL_H
#define RENDER_INTERNAL_H

#include "geom/packet.h"
#include "render.h"
#include "base/rng.h"
#include "sample/padding.h"
#include "sample/stream.h"

/* sampler_dims: all: the sets' slots. Two for the camera (lens point; shutter time in x), then
   per bounce the scatter direction, the light point and (the mixture's or glass's coin in x,
   the light's choice in y); with Russian roulette, then one more per bounce: its coin (x). */
#define DIMS_CAMERA 2
#define DIMS_PER_BOUNCE 3
enum { DIM_DIR, DIM_LIGHT, DIM_CHOICE, DIM_ROULETTE };

struct render_ctx {
    const struct scene *sc;
    const struct camera *cam;
    struct render_settings rs;
    struct sampler *pixel, *light;
    struct pt2 *pixel_pts;
    struct stream_source light_source;     /* the light sampler's, shared by the lights' streams */
    struct stream *lp;                     /* one per scene light: its points (sample/stream.h) */
    int *uses_points;                      /* per light: shape_light_uses_points, looked up once */
    const struct material **prim_material; /* each prim's material: one load after a hit */
    struct rng light_rng;
    struct render_stats *st;
    int timed; /* the current pixel is timed (sampler_timed): its light draws add to timed_draw_ns */
    struct packet_scene *packet; /* NULL, or four paths at once through packet_hit */
    /* sampler_dims: all: the pixel sampler's padded sets (sample/padding.h), DIMS_CAMERA +
       DIMS_PER_BOUNCE * dims_bounces slots, then dims_bounces more with Russian roulette (its
       coins: render_dims_slot); bounces past dims_bounces draw from the path's rng */
    struct padding pad;
    int dims_bounces;
};

/* A shadow ray of next-event estimation not traced yet, and what an emitter it reaches first
   adds: weight x its emission x scale (render_path.h's path_shadow_add); pending until then. */
struct path_shadow {
    ray r;
    vec3 weight;
    double scale;
    int pending;
};

/* Where a vertex's decisions come from: under sampler_dims: all (dims) sample's points of the
   pixel's sets for the vertex's bounce (depth), while that bounce has sets; else the path's rng.
   roulette: Russian roulette may end the path after the vertex (render_path.h's path_survives).
   shadow: NULL, or where next-event estimation leaves its shadow ray for the caller to trace. */
struct path_at {
    int dims, depth;
    uint32_t sample;
    int roulette;
    struct path_shadow *shadow;
};

/* The padded set of decision k of bounce depth (< ctx->dims_bounces): the roulette coins' sets
   follow every bounce's other three, so that a render without roulette keeps the sets (and the
   images) it had before roulette. */
static inline int render_dims_slot(const struct render_ctx *ctx, int depth, int k)
{
    return k == DIM_ROULETTE ? DIMS_CAMERA + DIMS_PER_BOUNCE * ctx->dims_bounces + depth
                             : DIMS_CAMERA + DIMS_PER_BOUNCE * depth + k;
}

/* render_pixel's samples (n of them, the pixel's points in ctx->pixel_pts) four paths at a
   time through packet_hit (render_lanes.c; ctx->packet set), each sample's rng started from the
   pixel's path stream *base; mix: the scene's lights are sampled by the mixture, nee: by
   next-event estimation; how: sampler_dims: all (dims) and Russian roulette (roulette); last:
   max_depth - 1. Their finite estimates go into sum (add_estimate), the count of the others
   into *nonfinite, their segments into *rays. */
void render_pixel_packet(struct render_ctx *ctx, int x, int y, size_t n, const struct rng *base, int mix,
                         int nee, struct path_at how, int last, double sum[3], uint64_t *nonfinite,
                         uint64_t *rays);

#endif
