/* render_light: the light strategy's direction: one light chosen from a light set and a point
   on it, from the light sampler's streams and the path's rng, or (sampler_dims: all) from the
   pixel's padded sets. Internal to common/render/, static. */
#ifndef RENDER_LIGHT_H
#define RENDER_LIGHT_H

#include "render_internal.h"
#include "geom/shape_light_inline.h"

/* A unit direction toward one of ls's lights, chosen uniformly (slots: each one's index in the
   scene's lights, NULL when ls is every light); disk and rect lights take their next point from
   their stream of the light sampler's points, a sphere its cone sample from rng. *light is the
   chosen light's index in ls and *pdf its density for the direction. */
static inline __attribute__((always_inline)) vec3 light_direction(struct render_ctx *ctx, struct light_set ls,
                                                                  const int *slots, vec3 o, struct rng *rng,
                                                                  int *light, double *pdf)
{
    const struct scene *sc = ctx->sc;
    const int j = (int)rng_below(rng, (uint32_t)ls.n), i = slots ? slots[j] : j;
    const struct prim *lp = &sc->prims[ls.prims[j]];
    struct pt2 s, turn = {0, 0};
    int turned = 0;
    if (ctx->uses_points[i]) {
        ctx->light_points++;
        s = stream_next(&ctx->light_source, &ctx->lp[i], &ctx->light_rng, &turn, &turned);
        if (turned)
            stream_prefetch(&ctx->light_source, ctx->lp, sc->n_lights, &ctx->light_rng);
    } else {
        s.x = rng_uniform32(rng);
        s.y = rng_uniform32(rng);
    }
    *light = j;
    return turned ? light_sample_turn(lp, o, s, turn.x, turn.y, pdf) : light_sample(lp, o, s, pdf);
}

/* light_direction under sampler_dims: all: ls's light chosen by choice in [0, 1), its point s. */
static inline __attribute__((always_inline)) vec3 light_direction_at(struct render_ctx *ctx,
                                                                     struct light_set ls, vec3 o,
                                                                     double choice, struct pt2 s, int *light,
                                                                     double *pdf)
{
    int i = (int)(choice * ls.n);
    i = i < ls.n ? i : ls.n - 1;
    *light = i;
    return light_sample(&ctx->sc->prims[ls.prims[i]], o, s, pdf);
}

#endif
