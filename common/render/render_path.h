/* render_path: the integrator, written once for the paths that trace (render.c) and the packet's
   lanes (render_lanes.c): next-event estimation, a segment's scatter at each material, Russian
   roulette and a sample's estimate into its pixel. Its parts: render_light.h (light choice and
   points), render_dir.h (directions), render_material.h (albedo, Schlick), render_decide.h
   (sampler_dims: all's decisions), render_time.h (the sampler's timing). Internal to common/;
   static, so each of the two keeps its own inlined copies. */
#ifndef RENDER_PATH_H
#define RENDER_PATH_H

#include <float.h>

#include "render_decide.h"
#include "render_dir.h"
#include "render_internal.h"
#include "render_light.h"
#include "render_material.h"
#include "render_time.h"
#include "geom/bvh.h"

/* A camera sample's estimate c into the pixel's sums when finite; a NaN or infinite one counts
   as zero (pbrt's rule: the pixel still divides by all its samples) and in *nonfinite. */
static inline void add_estimate(vec3 c, double sum[3], uint64_t *nonfinite)
{
    if (!v3_finite(c)) {
        ++*nonfinite;
        return;
    }
    sum[0] += c.x, sum[1] += c.y, sum[2] += c.z;
}

/* A shadow ray's emission (got: it hit something, hit its nearest hit) into *L: an emitter's front
   reached first counts, weighted by sh's weight and scale; sh is then done. */
static inline __attribute__((always_inline)) void
path_shadow_add(const struct render_ctx *ctx, struct path_shadow *sh, int got, const struct hit *hit, vec3 *L)
{
    sh->pending = 0;
    if (!got)
        return;
    const struct material *lm = ctx->prim_material[hit->prim];
    if (lm->type != MAT_LIGHT || !hit->front)
        return;
    *L = v3_add(*L, v3_mul(sh->weight, v3_scale(lm->emit, sh->scale)));
}

/* Next-event estimation at a scattering vertex h (diffuse surface or medium), before its own
   scatter: one light point from the light sampler's sets, a shadow ray toward it, and the
   emission it reaches weighted by the power heuristic against the material's own sampling
   (Veach 1997, ch. 9). f is the scattering function times the cosine (or the phase), bsdf_pdf
   the material's pdf for that direction; both per the direction, so given as closures over h:
   lambertian (cosine / pi) when phase is 0, else the isotropic phase. The light point comes from
   an emitter (light_set_emitters: a sample: true object that does not emit is the mixture's
   alone), chosen uniformly; the light strategy's pdf is the emitters' mixture, so an emitter the
   shadow ray reaches first counts whichever one was chosen. When at.shadow is set the shadow ray
   is left there for the caller to trace (the lanes trace four at a time), path_shadow_add then
   adding what it reaches; else it is traced here. */
static inline __attribute__((always_inline)) void
path_next_event(struct render_ctx *ctx, struct path_state *p, struct rng *rng, const struct hit *h,
                vec3 albedo, double phase, uint64_t *shadow_rays, struct path_at at)
{
    const struct scene *sc = ctx->sc;
    const struct light_set emitters = light_set_emitters(sc);
    int light = -1;
    double light_pdf = 0;
    vec3 dir;
    if (at.dims) {
        /* one emitter: no choice to make, so its padded set is not read (each sample's points of
           the other sets are the same whether it reads this one or not); past the padded bounces
           the path's rng still draws it, the draws after it unchanged */
        const double choice =
            emitters.n > 1 || at.depth >= ctx->dims_bounces ? path_decide(ctx, rng, at, DIM_CHOICE).y : 0;
        dir = light_direction_at(ctx, emitters, h->p, choice, path_decide(ctx, rng, at, DIM_LIGHT), &light,
                                 &light_pdf);
    } else {
        dir = light_direction(ctx, emitters, sc->emitter_lights, h->p, rng, &light, &light_pdf);
    }
    double f_pdf; /* the material's pdf for dir, which is also its f times cosine / albedo */
    if (phase > 0) {
        f_pdf = phase;
    } else {
        double cosine = v3_dot(dir, h->n);
        if (!(cosine > 0))
            return;
        f_pdf = cosine / PI;
    }
    double pl = lights_pdf_in(sc, emitters, h->p, dir, light, light_pdf);
    if (!(pl > 0))
        return;
    double w = pl * pl / (pl * pl + f_pdf * f_pdf);
    struct path_shadow sh = {{h->p, dir, p->r.time}, v3_mul(p->beta, albedo), f_pdf * w / pl, 1};
    ++*shadow_rays;
    if (at.shadow) {
        *at.shadow = sh;
        return;
    }
    struct hit hit;
    path_shadow_add(ctx, &sh, bvh_hit(sc, &sh.r, HIT_EPS, DBL_MAX, &hit), &hit, &p->L);
}

/* One path segment's interaction at h, the nearest hit of p->r (trace's loop body and the packet
   lanes' shade, written once): 1 with p's ray and throughput set for the next segment, 0 when the
   path ends (p->L is then its estimate). On the last segment (at.depth == at.last) only a light's
   emission counts (a scattered ray would never be traced, so no direction, light point or pdf is
   drawn). at.lights: with the mixture the scene's lights are sampled by the books' pdf mixture;
   with nee by next-event estimation with MIS, p->mis_pdf carrying the last scatter's pdf and
   *shadow_rays counting the shadow rays. at.medium_inline: a medium's scatter (its uniform direction and
   mixture pdf) inline, as a surface's (trace: final's fog scatters on most paths), else through
   calls (the lanes, whose scenes hold no media: inline there it cost checker ~1% and
   cornell-book3 7 instructions a sample by the code it moved). Always inline: the caller's ray,
   weight and radiance stay in its registers (a texture's lookup reads h through a copy). */
static inline __attribute__((always_inline)) int path_scatter(struct render_ctx *ctx, struct path_state *p,
                                                              struct rng *rng, const struct hit *h,
                                                              uint64_t *shadow_rays, struct path_at at)
{
    const struct scene *sc = ctx->sc;
    const struct material *m = ctx->prim_material[h->prim];
    if (at.depth == at.last && m->type != MAT_LIGHT)
        return 0;
    const int nee = at.lights == LIGHTS_NEE, mix = at.lights == LIGHTS_MIXTURE;
    vec3 dir;
    if (m->type == MAT_LAMBERTIAN) {
        vec3 albedo = surface_albedo(sc, m, h);
        if (nee) {
            path_next_event(ctx, p, rng, h, albedo, 0, shadow_rays, at);
            onb frame = onb_from_w(h->n);
            if (at.dims) {
                struct pt2 u = path_decide(ctx, rng, at, DIM_DIR);
                dir = cosine_direction_uv(&frame, u.x, u.y);
            } else {
                dir = cosine_direction(&frame, rng);
            }
            double cosine = v3_dot(dir, h->n);
            if (!(cosine > 0))
                return 0;
            p->mis_pdf = cosine / PI;
            p->beta = v3_mul(p->beta, albedo);
            p->r = (ray){h->p, dir, p->r.time};
            return 1;
        }
        int light = -1;
        double light_pdf = 0;
        if (at.dims) {
            struct pt2 c = path_decide(ctx, rng, at, DIM_CHOICE);
            if (mix && c.x < 0.5) {
                dir = light_direction_at(ctx, light_set_all(sc), h->p, c.y,
                                         path_decide(ctx, rng, at, DIM_LIGHT), &light, &light_pdf);
            } else {
                onb frame = onb_from_w(h->n);
                struct pt2 u = path_decide(ctx, rng, at, DIM_DIR);
                dir = cosine_direction_uv(&frame, u.x, u.y);
            }
        } else if (mix && rng_u32(rng) >> 31) {
            dir = light_direction(ctx, light_set_all(sc), NULL, h->p, rng, &light, &light_pdf);
        } else {
            onb frame = onb_from_w(h->n);
            dir = cosine_direction(&frame, rng);
        }
        /* below the surface: the scattering pdf is 0 and so is the estimate */
        double cosine = v3_dot(dir, h->n);
        if (!(cosine > 0))
            return 0;
        double cosine_pdf = cosine / PI; /* once: GCC divided again after the mixture */
        double pdf = mix ? 0.5 * lights_pdf(sc, h->p, dir, light, light_pdf) + 0.5 * cosine_pdf : cosine_pdf;
        if (!(pdf > 0))
            return 0;
        p->beta = v3_mul(p->beta, v3_scale(albedo, cosine_pdf / pdf));
        p->r = (ray){h->p, dir, p->r.time};
        return 1;
    }
    switch (m->type) {
    case MAT_LIGHT:
        if (!h->front)
            return 0;
        if (nee && p->mis_pdf > 0) { /* reached by a scatter that next-event estimation also sampled */
            double pl = lights_pdf_in(sc, light_set_emitters(sc), p->r.orig, p->r.dir, -1, 0),
                   pb = p->mis_pdf;
            p->L = v3_add(p->L, v3_mul(p->beta, v3_scale(m->emit, pb * pb / (pb * pb + pl * pl))));
        } else {
            p->L = v3_add(p->L, v3_mul(p->beta, m->emit));
        }
        return 0;
    case MAT_METAL:
        dir = v3_fma(v3_reflect(v3_unit(p->r.dir), h->n),
                     at.dims ? in_unit_ball(ctx, rng, at) : random_in_unit_sphere(rng), m->fuzz);
        if (v3_dot(dir, h->n) <= 0)
            return 0;
        p->beta = v3_mul(p->beta, m->albedo);
        break;
    case MAT_DIELECTRIC: {
        vec3 unit_dir = v3_unit(p->r.dir);
        double ratio = h->front ? 1.0 / m->ior : m->ior;
        double cos_t = d_min(v3_dot(v3_neg(unit_dir), h->n), 1.0);
        double sin_t = sqrt(1 - cos_t * cos_t);
        dir = (ratio * sin_t > 1 ||
               reflectance(cos_t, ratio) >
                   (at.dims ? path_decide(ctx, rng, at, DIM_CHOICE).x : rng_uniform32(rng)))
                  ? v3_reflect(unit_dir, h->n)
                  : v3_refract(unit_dir, h->n, ratio);
        break;
    }
    default: { /* MAT_ISOTROPIC */
        vec3 albedo = surface_albedo(sc, m, h);
        const double phase = 1 / (4 * PI);
        double pdf = phase;
        struct pt2 u = {0, 0}, c = {0, 0};
        if (at.dims) {
            u = path_decide(ctx, rng, at, DIM_DIR);
            c = path_decide(ctx, rng, at, DIM_CHOICE);
        }
        int light = -1;
        double light_pdf = 0;
        if (nee)
            path_next_event(ctx, p, rng, h, albedo, phase, shadow_rays, at);
        if (mix && (at.dims ? c.x < 0.5 : rng_u32(rng) >> 31)) /* the mixture's coin: toward a light */
            dir = at.dims ? light_direction_at(ctx, light_set_all(sc), h->p, c.y,
                                               path_decide(ctx, rng, at, DIM_LIGHT), &light, &light_pdf)
                          : light_direction(ctx, light_set_all(sc), NULL, h->p, rng, &light, &light_pdf);
        else
            dir = at.dims            ? uniform_sphere_direction_uv(u.x, u.y)
                  : at.medium_inline ? uniform_sphere_direction_inline(rng)
                                     : uniform_sphere_direction(rng);
        if (nee)
            p->mis_pdf = phase;
        else if (mix)
            pdf = 0.5 * (at.medium_inline ? lights_pdf(sc, h->p, dir, light, light_pdf)
                                          : shape_lights_pdf(sc, h->p, dir, light, light_pdf)) +
                  0.5 * phase;
        p->beta = v3_mul(p->beta, v3_scale(albedo, phase / pdf));
        p->r = (ray){h->p, dir, p->r.time};
        return 1;
    }
    }
    /* metal and glass: a specular bounce, whose emission reached counts whole */
    p->r = (ray){h->p, dir, p->r.time};
    if (nee)
        p->mis_pdf = 0;
    return 1;
}

/* Russian roulette after the scatter at vertex at (Arvo and Kirk, "Particle Transport and Image
   Synthesis", SIGGRAPH 1990), when at.roulette: from the second scatter on (as pbrt-v4's path
   integrator), a path whose throughput's largest channel m is below ROULETTE_WEIGHT goes on with
   probability m / ROULETTE_WEIGHT, its throughput divided by that, so that its expectation is
   unchanged: a weight window at 1/2 (Booth, "A Sample Problem for Variance Reduction in MCNP",
   1985), where pbrt-v4's is at 1; BENCH.md has the error per CPU second of both. The coin is the
   vertex's decision DIM_ROULETTE (x) under sampler_dims: all, else the path's rng. 1: goes on. */
#define ROULETTE_FROM_DEPTH 1
#define ROULETTE_WEIGHT 0.5
static inline __attribute__((always_inline)) int path_survives(struct render_ctx *ctx, struct path_state *p,
                                                               struct rng *rng, struct path_at at)
{
    if (!at.roulette || at.depth < ROULETTE_FROM_DEPTH)
        return 1;
    const double m = d_max(p->beta.x, d_max(p->beta.y, p->beta.z)) / ROULETTE_WEIGHT;
    if (!(m < 1))
        return 1;
    const double coin = at.dims ? path_decide(ctx, rng, at, DIM_ROULETTE).x : rng_uniform32(rng);
    if (!(coin < m))
        return 0;
    p->beta = v3_scale(p->beta, 1 / m);
    return 1;
}

#endif
