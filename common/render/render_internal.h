/* render_internal: the render context that render.c and render_ctx.c share. Internal to
   common/. */
#ifndef RENDER_INTERNAL_H
#define RENDER_INTERNAL_H

#include "geom/packet.h"
#include "render_types.h"
#include "geom/camera.h"
#include "geom/scene.h"
#include "sample/sampler.h"
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
    uint64_t light_points, padded_points; /* the pixel's so far: render_stats' work counts */
    struct packet_scene *packet;          /* NULL, or four paths at once through packet_hit */
    /* sampler_dims: all: the pixel sampler's padded sets (sample/padding.h), DIMS_CAMERA +
       DIMS_PER_BOUNCE * dims_bounces slots, then dims_bounces more with Russian roulette (its
       coins: render_dims_slot); bounces past dims_bounces draw from the path's rng */
    struct padding pad;
    int dims_bounces;
    /* the scene's hits depend on a ray's time: a moving sphere, or a medium (its free flight hashes
       the ray, time included); else sampler_dims: all reads no shutter time */
    int time_matters;
};

/* A shadow ray of next-event estimation not traced yet, and what an emitter it reaches first
   adds: weight x its emission x scale (render_path.h's path_shadow_add); pending until then. */
struct path_shadow {
    ray r;
    vec3 weight;
    double scale;
    int pending;
};

/* The render's light strategy: none (light_sampling: off, or a scene without lights: the
   material's own sampling alone), the books' pdf mixture, or next-event estimation with MIS. */
enum path_lights { LIGHTS_NONE, LIGHTS_MIXTURE, LIGHTS_NEE };

/* A camera path between segments: its ray, its throughput (beta), its radiance so far (L) and,
   for next-event estimation, the last scatter's pdf (0 after the camera or a mirror or glass: the
   emission it reaches then counts whole). trace's locals, a lane's struct path (render_lanes.c). */
struct path_state {
    ray r;
    vec3 beta, L;
    double mis_pdf;
};

/* How a vertex is handled. The render's: its light strategy (lights), sampler_dims: all (dims),
   Russian roulette (roulette: it may end the path after the vertex, render_path.h's
   path_survives), the last segment's depth (last: max_depth - 1) and whether a medium's scatter
   is inlined (medium_inline: trace's, where final's fog scatters on most paths; the lanes' scenes
   hold no media and call out). The vertex's: its bounce (depth), its camera sample's index in the
   pixel (sample: under dims the vertex's decisions are that sample's points of the pixel's sets
   while the bounce has sets, else the path's rng draws them) and shadow: NULL, or where
   next-event estimation leaves its shadow ray for the caller to trace. */
struct path_at {
    enum path_lights lights;
    int dims, roulette, last, medium_inline;
    int depth;
    uint32_t sample;
    struct path_shadow *shadow;
};

/* A pixel's sums over its camera samples: the finite estimates (add_estimate), the count of the
   others (nonfinite), the path segments traced (rays) and the shadow rays (shadow). */
struct pixel_sums {
    double sum[3];
    uint64_t nonfinite, rays, shadow;
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
   pixel's path stream *base; how: the render's part of path_at (its depth, sample and shadow are
   the lanes'). Their estimates and segments are added to *ps. */
void render_pixel_packet(struct render_ctx *ctx, int x, int y, size_t n, const struct rng *base,
                         struct path_at how, struct pixel_sums *ps);

#endif
