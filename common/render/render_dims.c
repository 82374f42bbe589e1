/* render_dims: sampler_dims: all. Every 2D decision of a path takes its point from a per-pixel
   set of the job's pixel sampler, one set per decision and bounce, in a random order of its own
   so that the sets of different decisions are not correlated ("padding": pbrt's stratified and
   padded samplers, Pharr et al., PBR 3rd ed. 7.3 and 7.4). Grid sets (uniform, jitter, random)
   make sample s's point alone when it is asked for (render_dims_grid_point); Poisson and Sobol
   sets are drawn whole when a path of the pixel first needs them, then shuffled. */
#include <stdlib.h>

#include "render_path.h"

/* Buffers for at most this many bytes of sets; past it fewer bounces are stratified. */
#define DIMS_MAX_BYTES ((size_t)256 << 20)
/* Bounces with sets of their own; the decisions of later ones draw from the path's rng. */
#define DIMS_MAX_BOUNCES 16

int render_dims_init(struct render_ctx *ctx, struct err *e)
{
    ctx->dims_grid = sampler_grid_of(ctx->pixel);
    if (sampler_cells(ctx->pixel) > 0) { /* grid sets: nothing stored, every bounce stratified */
        ctx->dims_grid_sets = 1;
        ctx->dims_bounces = ctx->rs.max_depth;
        return 0;
    }
    const size_t cap = sampler_set_capacity(ctx->pixel);
    /* a fresh Poisson set may hold fewer points than the pixel's: sets are appended until n */
    const size_t per_slot = sampler_cells(ctx->pixel) > 0 ? cap : 2 * cap;
    int bounces = ctx->rs.max_depth < DIMS_MAX_BOUNCES ? ctx->rs.max_depth : DIMS_MAX_BOUNCES;
    const int per_bounce = DIMS_PER_BOUNCE + (ctx->rs.russian_roulette != 0); /* + DIM_ROULETTE's */
    while (bounces > 1 &&
           (size_t)(DIMS_CAMERA + per_bounce * bounces) * per_slot * sizeof(struct pt2) > DIMS_MAX_BYTES)
        bounces--;
    ctx->dims_bounces = bounces;
    ctx->dims_slots = DIMS_CAMERA + per_bounce * bounces;
    ctx->dims_slot_cap = per_slot;
    ctx->dims_pts = malloc((size_t)ctx->dims_slots * per_slot * sizeof *ctx->dims_pts);
    ctx->dims_gen = calloc((size_t)ctx->dims_slots, sizeof *ctx->dims_gen);
    if (!ctx->dims_pts || !ctx->dims_gen)
        return err_set(e, NULL, 0, 0,
                       "out of memory for sampler_dims: all's point sets (%d of them, %zu points each)",
                       ctx->dims_slots, per_slot);
    return 0;
}

void render_dims_fill(struct render_ctx *ctx, int slot)
{
    struct pt2 *pts = ctx->dims_pts + (size_t)slot * ctx->dims_slot_cap;
    const size_t n = ctx->dims_n, cap = sampler_set_capacity(ctx->pixel);
    const uint64_t t0 = ctx->timed ? now_ns() : 0;
    struct rng r;
    rng_pixel(&r, ctx->rs.seed, ctx->px, ctx->py, 16 + (uint64_t)slot);
    size_t have = 0;
    while (have < n && have + cap <= ctx->dims_slot_cap) {
        have += sampler_draw(ctx->pixel, &r, pts + have);
    }
    /* the first n places of a Fisher-Yates shuffle: sample s takes a uniformly random point */
    for (size_t k = 0; k < n && k < have; k++) {
        size_t j = k + rng_below(&r, (uint32_t)(have - k));
        struct pt2 t = pts[k];
        pts[k] = pts[j];
        pts[j] = t;
    }
    for (size_t k = have; k < n; k++) { /* unreachable for the shipped samplers: a set is never empty */
        pts[k].x = rng_uniform(&r);
        pts[k].y = rng_uniform(&r);
    }
    ctx->dims_gen[slot] = ctx->dims_pixel;
    if (ctx->timed)
        ctx->st->timed_draw_ns += now_ns() - t0;
}
