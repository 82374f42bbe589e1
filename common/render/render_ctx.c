/* render_ctx: the render context's buffers and tables, made once per process, and the render's
   counters. */
#include <stdlib.h>

#include "render.h"
#include "render_internal.h"

void render_stats_init(struct render_stats *st)
{
    *st = (struct render_stats){0};
    st->spp_min = UINT32_MAX;
}

void render_stats_add(struct render_stats *into, const struct render_stats *from)
{
    into->pixels += from->pixels;
    into->samples += from->samples;
    into->rays += from->rays;
    into->shadow_rays += from->shadow_rays;
    into->light_sets += from->light_sets;
    into->pixel_points += from->pixel_points;
    into->light_points += from->light_points;
    into->padded_points += from->padded_points;
    into->padded_sets += from->padded_sets;
    into->nonfinite += from->nonfinite;
    into->timed_pixel_ns += from->timed_pixel_ns;
    into->timed_draw_ns += from->timed_draw_ns;
    into->sampler_s += from->sampler_s;
    if (from->spp_min < into->spp_min)
        into->spp_min = from->spp_min;
    if (from->spp_max > into->spp_max)
        into->spp_max = from->spp_max;
}

void render_stats_finish(struct render_stats *st, double cpu_s)
{
    const double share = st->timed_pixel_ns > 0 ? (double)st->timed_draw_ns / (double)st->timed_pixel_ns : 0;
    st->sampler_s = cpu_s > 0 ? share * cpu_s : 0;
}

/* sampler_dims: all's sets, at most this many bytes of them; past it fewer bounces are padded. */
#define DIMS_MAX_BYTES ((size_t)256 << 20)
/* Bounces with sets of their own; the decisions of later ones draw from the path's rng. */
#define DIMS_MAX_BOUNCES 16

/* The padded sets of sampler_dims: all for ctx->rs. 0, or -1 with e filled. */
static int dims_init(struct render_ctx *ctx, struct err *e)
{
    const size_t per_slot = padding_slot_points(ctx->pixel);
    int bounces = ctx->rs.max_depth < DIMS_MAX_BOUNCES ? ctx->rs.max_depth : DIMS_MAX_BOUNCES;
    const int per_bounce = DIMS_PER_BOUNCE + (ctx->rs.russian_roulette != 0); /* + DIM_ROULETTE's */
    while (bounces > 1 &&
           (size_t)(DIMS_CAMERA + per_bounce * bounces) * per_slot * sizeof(struct pt2) > DIMS_MAX_BYTES)
        bounces--;
    ctx->dims_bounces = bounces;
    return padding_init(&ctx->pad, ctx->pixel, DIMS_CAMERA + per_bounce * bounces, e);
}

void render_ctx_free(struct render_ctx *ctx)
{
    if (!ctx)
        return;
    if (ctx->lp)
        for (int i = 0; i < ctx->sc->n_lights; i++)
            stream_release(&ctx->lp[i]);
    free(ctx->lp);
    free(ctx->uses_points);
    stream_source_release(&ctx->light_source);
    free(ctx->prim_material);
    packet_scene_free(ctx->packet);
    free(ctx->pixel_pts);
    padding_release(&ctx->pad);
    free(ctx);
}

struct render_ctx *render_ctx_new(const struct scene *sc, const struct camera *cam,
                                  const struct render_settings *rs, struct sampler *pixel,
                                  struct sampler *light, struct err *e)
{
    struct render_ctx *ctx = calloc(1, sizeof *ctx);
    if (!ctx)
        goto oom;
    ctx->sc = sc;
    ctx->cam = cam;
    ctx->rs = *rs;
    ctx->pixel = pixel;
    ctx->light = light;
    ctx->pixel_pts = malloc(sampler_set_capacity(pixel) * sizeof *ctx->pixel_pts);
    ctx->lp = calloc((size_t)sc->n_lights + 1, sizeof *ctx->lp);
    ctx->uses_points = calloc((size_t)sc->n_lights + 1, sizeof *ctx->uses_points);
    ctx->prim_material = malloc(((size_t)sc->n_prims + 1) * sizeof *ctx->prim_material);
    if (packet_usable(sc) && !(ctx->packet = packet_scene_new(sc)))
        goto oom;
    if (!ctx->pixel_pts || !ctx->lp || !ctx->uses_points || !ctx->prim_material)
        goto oom;
    if (rs->dims_all && dims_init(ctx, e) < 0)
        goto fail;
    for (int i = 0; i < sc->n_prims; i++) {
        ctx->prim_material[i] = &sc->materials[sc->prims[i].material];
        ctx->time_matters |= sc->prims[i].type == PRIM_MOVING_SPHERE || sc->prims[i].type == PRIM_MEDIUM;
    }
    if (light && stream_source_init(&ctx->light_source, light, e) < 0)
        goto fail;
    for (int i = 0; i < sc->n_lights; i++) {
        ctx->uses_points[i] = shape_light_uses_points(&sc->prims[sc->lights[i]]);
        if (rs->light_sampling_off || !ctx->uses_points[i])
            continue;
        if (!light) {
            err_set(e, NULL, 0, 0, "internal: scene has a disk or rect light but no light sampler");
            goto fail;
        }
        if (stream_init(&ctx->lp[i], &ctx->light_source) < 0)
            goto oom;
    }
    return ctx;
oom:
    err_set(e, NULL, 0, 0, "out of memory for the render's sample buffers");
fail:
    render_ctx_free(ctx);
    return NULL;
}
