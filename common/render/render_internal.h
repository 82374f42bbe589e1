/* render_internal: the render context that render.c and render_ctx.c share. Internal to
   common/. */
#ifndef RENDER_INTERNAL_H
#define RENDER_INTERNAL_H

#include "geom/packet.h"
#include "render.h"
#include "base/rng.h"
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
   the light's choice in y); with Russian roulette, then one more per bounce: its coin (x). */
#define DIMS_CAMERA 2
#define DIMS_PER_BOUNCE 3
enum { DIM_DIR, DIM_LIGHT, DIM_CHOICE, DIM_ROULETTE };

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
    /* sampler_dims: all (render_dims.c): dims_slots sets of up to dims_slot_cap points in one
       array, slot k valid for the current pixel when dims_gen[k] == dims_pixel; the pixel's
       (px, py) and its sample count dims_n; bounces past dims_bounces draw from the path's rng */
    struct pt2 *dims_pts;
    uint64_t *dims_gen, dims_pixel;
    uint64_t dims_key;             /* the pixel's key for grid sets (render_dims_grid_point) */
    struct sampler_grid dims_grid; /* the pixel sampler's grid */
    int dims_grid_sets;            /* 1: the pixel sampler is uniform, jitter or random */
    size_t dims_slot_cap, dims_n;
    int dims_slots, dims_bounces, px, py;
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

/* render_pixel's samples (n of them, the pixel's points in ctx->pixel_pts) four paths at a
   time through packet_hit (render_lanes.c; ctx->packet set), each sample's rng started from the
   pixel's path stream *base; mix: the scene's lights are sampled by the mixture, nee: by
   next-event estimation; how: sampler_dims: all (dims) and Russian roulette (roulette); last:
   max_depth - 1. Their estimates go into sum and kept (add_estimate), the dropped ones into
   *nonfinite, their segments into *rays. */
void render_pixel_packet(struct render_ctx *ctx, int x, int y, size_t n, const struct rng *base, int mix,
                         int nee, struct path_at how, int last, double sum[3], size_t *kept,
                         uint64_t *nonfinite, uint64_t *rays);

/* Allocate the sets of sampler_dims: all (ctx->rs.dims_all). 0, or -1 with e filled. */
int render_dims_init(struct render_ctx *ctx, struct err *e);

/* Draw slot's set for the current pixel: ctx->dims_n points of the pixel sampler, shuffled. */
void render_dims_fill(struct render_ctx *ctx, int slot);

/* A bijection of [0, n) keyed by key, after Kensler ("Correlated Multi-Jittered Sampling", Pixar
   2013): steps that are each invertible on the w bits of the next power of two (xor, multiply by
   an odd number, xorshift right, add), walked until the value lands below n. */
static inline uint32_t render_dims_permute(uint32_t i, uint32_t n, uint64_t key)
{
    uint32_t mask = n - 1;
    mask |= mask >> 1, mask |= mask >> 2, mask |= mask >> 4, mask |= mask >> 8, mask |= mask >> 16;
    const uint32_t k0 = (uint32_t)key, k1 = (uint32_t)(key >> 32);
    do {
        i = (i ^ k0) & mask;
        i = (i * 0x9e3779b1u) & mask;
        i ^= i >> 7;
        i = (i + k1) & mask;
        i = (i * 0x85ebca6bu) & mask;
        i ^= i >> 11;
        i = (i * 0xc2b2ae35u) & mask;
        i ^= i >> 5;
    } while (i >= n);
    return i;
}

/* The slot of decision k of bounce depth (< ctx->dims_bounces): the roulette coins' slots follow
   every bounce's other three, so that a render without roulette keeps the slots (and the images)
   it had before roulette. */
static inline int render_dims_slot(const struct render_ctx *ctx, int depth, int k)
{
    return k == DIM_ROULETTE ? DIMS_CAMERA + DIMS_PER_BOUNCE * ctx->dims_bounces + depth
                             : DIMS_CAMERA + DIMS_PER_BOUNCE * depth + k;
}

/* Sample s's point of grid set `slot`: the cell a keyed permutation gives s, the point in it from
   a hash of the slot's key and the cell (uniform: its centre; random: any cell's hash, no cells). */
static inline struct pt2 render_dims_grid_point(const struct render_ctx *ctx, int slot, uint32_t s)
{
    const struct sampler_grid *g = &ctx->dims_grid;
    const uint64_t key = rng_mix64(ctx->dims_key + (uint64_t)(slot + 1) * 0x9e3779b97f4a7c15ULL);
    const uint32_t cells = (uint32_t)g->n * (uint32_t)g->n;
    const uint32_t cell = g->kind == SAMPLER_RANDOM ? s : render_dims_permute(s, cells, key);
    const uint64_t h0 = rng_mix64(key ^ ((uint64_t)cell << 1 | 1)), h1 = rng_mix64(h0);
    const double u = (double)(h0 >> 11) * 0x1.0p-53, v = (double)(h1 >> 11) * 0x1.0p-53;
    const int n = g->n, j = (int)(cell / (uint32_t)n), i = (int)(cell - (uint32_t)j * (uint32_t)n);
    switch (g->kind) {
    case SAMPLER_UNIFORM:
        return (struct pt2){(i + 0.5) / n, (j + 0.5) / n};
    case SAMPLER_JITTER:
        return (struct pt2){sampler_cell_coord(i, u, n), sampler_cell_coord(j, v, n)};
    default:
        return (struct pt2){u, v};
    }
}

/* Sample s's point of set `slot` of the current pixel: a grid set's made alone, another drawn
   whole on first use. */
static inline struct pt2 render_dims_point(struct render_ctx *ctx, int slot, uint32_t s)
{
    if (ctx->dims_grid_sets)
        return render_dims_grid_point(ctx, slot, s);
    if (ctx->dims_gen[slot] != ctx->dims_pixel)
        render_dims_fill(ctx, slot);
    return ctx->dims_pts[(size_t)slot * ctx->dims_slot_cap + s];
}

#endif
