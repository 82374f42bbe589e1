/* render_path: the integrator's steps that trace (render.c) and the packet's lanes
   (render_lanes.c) share: the light points, the scattered directions, albedo and Schlick's
   reflectance. Internal to common/; static, so each of the two keeps its own inlined copies. */
#ifndef RENDER_PATH_H
#define RENDER_PATH_H

#include <string.h>
#include <time.h>

#include "render_internal.h"
#include "geom/bvh.h"
#include "geom/shape_light_inline.h"
#include "geom/texture.h"

static __attribute__((unused)) uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* The sidecar's sampler_s: one pixel in SAMPLER_TIME_EVERY (by st->pixels) is timed whole, and
   every point-set draw inside it, in integer nanoseconds of one monotonic clock; the draws' share
   of those pixels' time, times the process's CPU time, estimates the CPU time spent drawing
   (render_stats_finish). The draws are intervals inside their pixel's, so the share cannot
   exceed 1. Timing one draw in eight and counting it for the next seven made the share 2.1 and
   more: a time slice lost in a timed draw counted eight times, and on a busy machine a wall
   clock runs on while a process waits. Timing every draw cost two clock reads per set, ~0.8% of
   final's time, more than drawing a jitter set. */
#define SAMPLER_TIME_EVERY 8
static inline int sampler_timed(uint64_t pixels)
{
    return pixels % SAMPLER_TIME_EVERY == 0;
}

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

/* cosine_direction_uv from r. Always inline: with nee's call beside the mixture's GCC kept it
   out of line, +2% of cornell-book3's instructions. */
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

static __attribute__((noinline, unused)) vec3 texture_albedo(const struct scene *sc, const struct material *m,
                                                             struct hit *h)
{
    const struct texture *t = &sc->textures[m->texture];
    if (texture_needs_uv(t))
        shape_uv(&sc->prims[h->prim], h);
    return texture_value(sc, t, h->u, h->v, h->p);
}

/* A plain material's albedo inline, a texture's lookup out of line (the call and its frame cost
   every untextured diffuse bounce ~20 instructions), on a copy of h, which the lookup fills with
   the uv: h itself then stays in the caller's registers. */
static inline __attribute__((always_inline)) vec3
surface_albedo(const struct scene *sc, const struct material *m, const struct hit *h)
{
    if (m->texture < 0)
        return m->albedo;
    struct hit copy = *h;
    return texture_albedo(sc, m, &copy);
}

static __attribute__((unused)) double reflectance(double cosine, double ref_idx)
{
    /* Schlick's approximation. */
    double r0 = (1 - ref_idx) / (1 + ref_idx);
    r0 *= r0;
    double x = 1 - cosine, x2 = x * x;
    return r0 + (1 - r0) * (x2 * x2 * x);
}

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

/* Decision k (DIM_DIR, DIM_LIGHT, DIM_CHOICE, DIM_ROULETTE) of the vertex at->depth: two uniforms. */
static inline __attribute__((always_inline)) struct pt2 path_decide(struct render_ctx *ctx, struct rng *rng,
                                                                    struct path_at at, int k)
{
    if (at.depth < ctx->dims_bounces)
        return padding_point(&ctx->pad, render_dims_slot(ctx, at.depth, k), at.sample);
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
   pixel's sets (each drawn only where the camera uses it). */
static inline __attribute__((always_inline)) ray render_camera_ray_dims(struct render_ctx *ctx, double u,
                                                                        double v, uint32_t s)
{
    const struct camera *cam = ctx->cam;
    struct pt2 lens = {0, 0}, time = {0, 0};
    if (cam->lens_radius > 0)
        lens = padding_point(&ctx->pad, 0, s);
    if (cam->time0 != cam->time1)
        time = padding_point(&ctx->pad, 1, s);
    return camera_ray_at(cam, u, v, lens.x, lens.y, time.x);
}

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
path_next_event(struct render_ctx *ctx, const ray *r, vec3 beta, vec3 *L, struct rng *rng,
                const struct hit *h, vec3 albedo, double phase, uint64_t *rays, struct path_at at)
{
    const struct scene *sc = ctx->sc;
    const struct light_set emitters = light_set_emitters(sc);
    int light = -1;
    double light_pdf = 0;
    vec3 dir;
    if (at.dims) {
        struct pt2 c = path_decide(ctx, rng, at, DIM_CHOICE);
        dir = light_direction_at(ctx, emitters, h->p, c.y, path_decide(ctx, rng, at, DIM_LIGHT), &light,
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
    struct path_shadow sh = {{h->p, dir, r->time}, v3_mul(beta, albedo), f_pdf * w / pl, 1};
    ++*rays;
    if (at.shadow) {
        *at.shadow = sh;
        return;
    }
    struct hit hit;
    path_shadow_add(ctx, &sh, bvh_hit(sc, &sh.r, HIT_EPS, DBL_MAX, &hit), &hit, L);
}

/* One path segment's interaction at h, the nearest hit of *r (trace's loop body and the packet
   lanes' shade, written once): 1 with *r and *beta set for the next segment, 0 when the path ends
   (*L is then its estimate). at_last: this is the last segment, where only a light's emission
   counts (a scattered ray would never be traced, so no direction, light point or pdf is drawn);
   mix: the scene's lights are sampled by the books' pdf mixture; nee (instead of mix): by
   next-event estimation with MIS, *mis_pdf carrying the last scatter's pdf (0 after the camera
   or a mirror or glass: its emission then counts whole) and *rays counting the shadow rays;
   media_inline: a medium's scatter (its uniform direction and mixture pdf) inline, as a
   surface's (path_scatter_as from trace: final's fog scatters on most paths), else through calls
   (path_scatter, for the lanes, whose scenes hold no media: inline in the lanes it cost checker
   ~1% and cornell-book3 7 instructions a sample by the code it moved). Always inline: the
   caller's ray, weight and radiance stay in its registers (a texture's lookup reads h through a
   copy). */
static inline __attribute__((always_inline)) int path_scatter_as(struct render_ctx *ctx, ray *r, vec3 *beta,
                                                                 vec3 *L, struct rng *rng,
                                                                 const struct hit *h, int at_last, int mix,
                                                                 int nee, double *mis_pdf, uint64_t *rays,
                                                                 struct path_at at, int media_inline)
{
    const struct scene *sc = ctx->sc;
    const struct material *m = ctx->prim_material[h->prim];
    if (at_last && m->type != MAT_LIGHT)
        return 0;
    vec3 dir;
    if (m->type == MAT_LAMBERTIAN) {
        vec3 albedo = surface_albedo(sc, m, h);
        if (nee) {
            path_next_event(ctx, r, *beta, L, rng, h, albedo, 0, rays, at);
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
            *mis_pdf = cosine / PI;
            *beta = v3_mul(*beta, albedo);
            *r = (ray){h->p, dir, r->time};
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
        *beta = v3_mul(*beta, v3_scale(albedo, cosine_pdf / pdf));
        *r = (ray){h->p, dir, r->time};
        return 1;
    }
    switch (m->type) {
    case MAT_LIGHT:
        if (!h->front)
            return 0;
        if (nee && *mis_pdf > 0) { /* reached by a scatter that next-event estimation also sampled */
            double pl = lights_pdf_in(sc, light_set_emitters(sc), r->orig, r->dir, -1, 0), pb = *mis_pdf;
            *L = v3_add(*L, v3_mul(*beta, v3_scale(m->emit, pb * pb / (pb * pb + pl * pl))));
        } else {
            *L = v3_add(*L, v3_mul(*beta, m->emit));
        }
        return 0;
    case MAT_METAL:
        dir = v3_fma(v3_reflect(v3_unit(r->dir), h->n),
                     at.dims ? in_unit_ball(ctx, rng, at) : random_in_unit_sphere(rng), m->fuzz);
        if (v3_dot(dir, h->n) <= 0)
            return 0;
        *beta = v3_mul(*beta, m->albedo);
        *r = (ray){h->p, dir, r->time};
        if (nee) /* a specular bounce: the emission it reaches counts whole */
            *mis_pdf = 0;
        return 1;
    case MAT_DIELECTRIC: {
        vec3 unit_dir = v3_unit(r->dir);
        double ratio = h->front ? 1.0 / m->ior : m->ior;
        double cos_t = d_min(v3_dot(v3_neg(unit_dir), h->n), 1.0);
        double sin_t = sqrt(1 - cos_t * cos_t);
        dir = (ratio * sin_t > 1 ||
               reflectance(cos_t, ratio) >
                   (at.dims ? path_decide(ctx, rng, at, DIM_CHOICE).x : rng_uniform32(rng)))
                  ? v3_reflect(unit_dir, h->n)
                  : v3_refract(unit_dir, h->n, ratio);
        *r = (ray){h->p, dir, r->time};
        if (nee) /* a specular bounce: the emission it reaches counts whole */
            *mis_pdf = 0;
        return 1;
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
        if (nee) {
            path_next_event(ctx, r, *beta, L, rng, h, albedo, phase, rays, at);
            dir = at.dims        ? uniform_sphere_direction_uv(u.x, u.y)
                  : media_inline ? uniform_sphere_direction_inline(rng)
                                 : uniform_sphere_direction(rng);
            *mis_pdf = phase;
        } else if (mix) {
            int light = -1;
            double light_pdf = 0;
            if (at.dims)
                dir = c.x < 0.5 ? light_direction_at(ctx, light_set_all(sc), h->p, c.y,
                                                     path_decide(ctx, rng, at, DIM_LIGHT), &light, &light_pdf)
                                : uniform_sphere_direction_uv(u.x, u.y);
            else
                dir = rng_u32(rng) >> 31
                          ? light_direction(ctx, light_set_all(sc), NULL, h->p, rng, &light, &light_pdf)
                      : media_inline ? uniform_sphere_direction_inline(rng)
                                     : uniform_sphere_direction(rng);
            pdf = 0.5 * (media_inline ? lights_pdf(sc, h->p, dir, light, light_pdf)
                                      : shape_lights_pdf(sc, h->p, dir, light, light_pdf)) +
                  0.5 * phase;
        } else {
            dir = at.dims        ? uniform_sphere_direction_uv(u.x, u.y)
                  : media_inline ? uniform_sphere_direction_inline(rng)
                                 : uniform_sphere_direction(rng);
        }
        *beta = v3_mul(*beta, v3_scale(albedo, phase / pdf));
        *r = (ray){h->p, dir, r->time};
        return 1;
    }
    }
}

/* Russian roulette after the scatter at vertex at (pbrt-v4's path integrator; Arvo and Kirk,
   "Particle Transport and Image Synthesis", SIGGRAPH 1990), when at.roulette: from the second
   scatter on, a path whose throughput's largest channel m is below 1 goes on with probability m,
   its throughput divided by m, so that its expectation is unchanged. The coin is the vertex's
   decision DIM_ROULETTE (x) under sampler_dims: all, else the path's rng. 1: the path goes on. */
#define ROULETTE_FROM_DEPTH 1
static inline __attribute__((always_inline)) int path_survives(struct render_ctx *ctx, vec3 *beta,
                                                               struct rng *rng, struct path_at at)
{
    if (!at.roulette || at.depth < ROULETTE_FROM_DEPTH)
        return 1;
    const double m = d_max(beta->x, d_max(beta->y, beta->z));
    if (!(m < 1))
        return 1;
    const double coin = at.dims ? path_decide(ctx, rng, at, DIM_ROULETTE).x : rng_uniform32(rng);
    if (!(coin < m))
        return 0;
    *beta = v3_scale(*beta, 1 / m);
    return 1;
}

/* path_scatter_as with a medium's scatter through calls. */
static inline __attribute__((always_inline)) int path_scatter(struct render_ctx *ctx, ray *r, vec3 *beta,
                                                              vec3 *L, struct rng *rng, const struct hit *h,
                                                              int at_last, int mix, int nee, double *mis_pdf,
                                                              uint64_t *rays, struct path_at at)
{
    return path_scatter_as(ctx, r, beta, L, rng, h, at_last, mix, nee, mis_pdf, rays, at, 0);
}

#endif
