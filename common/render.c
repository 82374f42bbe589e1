/* render: per-pixel point sets, per-light point sets consumed in order, and the mixture-pdf
   path integrator of Shirley's "Ray Tracing: The Rest of Your Life" (50% light, 50% cosine). */
#include "render.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bvh.h"
#include "packet.h"
#include "render_internal.h"
#include "shape_light_inline.h"
#include "texture.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* Pooled sets: the pool point each light would take next if it were the next light sampled
   (the light rng's next draw picks it), fetched into the cache now. One of them is the next
   point taken unless its set runs out first; without this its load, an L2 hit at the head of
   the path's dependency chain, was about half of light_direction's time. */
static inline __attribute__((always_inline)) void prefetch_next_points(const struct render_ctx *ctx)
{
    const uint64_t u = rng_peek_u32(&ctx->light_rng);
    for (int i = 0; i < ctx->sc->n_lights; i++) {
        const struct light_points *lp = &ctx->lp[i];
        if (lp->next < lp->n) {
            size_t j = lp->next + (size_t)((u * (uint32_t)(lp->n - lp->next)) >> 32);
            __builtin_prefetch(&lp->pool[lp->cells[j]]);
        }
    }
}

/* Light i's points: next_light_point takes the next point of its current set, and
   refill_light_points draws a fresh set when it runs out (out of line: once per set). A pixel uses
   only part of a set, in order; a grid or Poisson set in generation order would then cover
   only part of the light (a grid's first rows, a Poisson blob around its first point) and
   bias the image, so the set is consumed in a random order: a Fisher-Yates shuffle done lazily,
   one swap per point taken. Every point consumed is then uniform over the light, and the set
   still stratifies what is consumed of it. Uniform and jitter sets shuffle their cells and make
   a cell's point when it is taken; a random set's points are independent, so any order of them
   is just the next point; a pooled Poisson set shuffles indices into the pool and shifts a
   point when it is taken. Only a fresh Poisson set is drawn whole. */
static __attribute__((noinline)) void refill_light_points(struct render_ctx *ctx, struct light_points *lp)
{
    const enum sampler_kind kind = ctx->light_kind;
    double t0 = now_s();
    if (lp->cells) {
        lp->n = kind == SAMPLER_POISSON
                    ? sampler_pool_set(ctx->light, &ctx->light_rng, &lp->pool, &lp->ox, &lp->oy)
                    : sampler_cells(ctx->light);
        if (kind != SAMPLER_RANDOM) /* a set per pixel and light, a few dozen points used */
            memcpy(lp->cells, ctx->identity, lp->n * sizeof *lp->cells);
        if (kind == SAMPLER_POISSON) {
            v3_sincos_turn(lp->oy, &lp->sin_oy, &lp->cos_oy);
        }
    } else {
        lp->n = sampler_draw(ctx->light, &ctx->light_rng, lp->pts);
    }
    lp->next = 0;
    ctx->st->sampler_s += now_s() - t0;
    ctx->st->light_sets++;
}

/* Inline with the grid kinds' cell point (sampler_grid_point): a light point costs no call. */
static inline __attribute__((always_inline)) struct pt2 next_light_point(struct render_ctx *ctx, int i,
                                                                         struct pt2 *turn, int *turned)
{
    struct light_points *lp = &ctx->lp[i];
    const enum sampler_kind kind = ctx->light_kind;
    if (lp->next >= lp->n)
        refill_light_points(ctx, lp);
    size_t k = lp->next++;
    if (kind == SAMPLER_RANDOM)
        return sampler_grid_point(&ctx->light_grid, 0, &ctx->light_rng);
    size_t j = k + rng_below(&ctx->light_rng, (uint32_t)(lp->n - k));
    if (lp->cells) {
        uint32_t cell = lp->cells[j];
        lp->cells[j] = lp->cells[k];
        lp->cells[k] = cell;
        if (kind == SAMPLER_POISSON) {
            /* the shifted point's angle 2 pi (y + oy): the point's own turned by the shift's */
            const struct pt2 t = lp->pool[cell].turn;
            *turn = (struct pt2){t.x * lp->cos_oy - t.y * lp->sin_oy, t.y * lp->cos_oy + t.x * lp->sin_oy};
            *turned = 1;
            prefetch_next_points(ctx);
            return sampler_shift(lp->pool[cell].p, lp->ox, lp->oy);
        }
        return sampler_grid_point(&ctx->light_grid, cell, &ctx->light_rng);
    }
    struct pt2 chosen = lp->pts[j];
    lp->pts[j] = lp->pts[k];
    lp->pts[k] = chosen;
    return chosen;
}

static vec3 random_in_unit_sphere(struct rng *r)
{
    for (;;) {
        vec3 p = v3(2 * rng_uniform32(r) - 1, 2 * rng_uniform32(r) - 1, 2 * rng_uniform32(r) - 1);
        if (v3_len2(p) < 1)
            return p;
    }
}

/* Cosine-weighted direction about n (Malley's method). */
static inline __attribute__((always_inline)) vec3 cosine_direction_inline(const onb *frame, struct rng *r)
{
    double u2 = rng_uniform32(r), s = sqrt(u2), sin_phi, cos_phi;
    v3_sincos_turn(rng_uniform32(r), &sin_phi, &cos_phi);
    return onb_local(frame, v3(cos_phi * s, sin_phi * s, sqrt(1 - u2)));
}

static vec3 uniform_sphere_direction(struct rng *r)
{
    double z = 1 - 2 * rng_uniform32(r), s = sqrt(d_max(0, 1 - z * z)), sin_phi, cos_phi;
    v3_sincos_turn(rng_uniform32(r), &sin_phi, &cos_phi);
    return v3(cos_phi * s, sin_phi * s, z);
}

static __attribute__((noinline)) vec3 texture_albedo(const struct scene *sc, const struct material *m,
                                                     struct hit *h)
{
    const struct texture *t = &sc->textures[m->texture];
    if (texture_needs_uv(t))
        shape_uv(&sc->prims[h->prim], h);
    return texture_value(sc, t, h->u, h->v, h->p);
}

/* A plain material's albedo inline, a texture's lookup out of line (the call and its frame cost
   every untextured diffuse bounce ~20 instructions). */
static inline vec3 surface_albedo(const struct scene *sc, const struct material *m, struct hit *h)
{
    return m->texture < 0 ? m->albedo : texture_albedo(sc, m, h);
}

static double reflectance(double cosine, double ref_idx)
{
    /* Schlick's approximation. */
    double r0 = (1 - ref_idx) / (1 + ref_idx);
    r0 *= r0;
    double x = 1 - cosine, x2 = x * x;
    return r0 + (1 - r0) * (x2 * x2 * x);
}

/* A unit direction toward one of the scene's lights, chosen uniformly; disk and rect lights
   take their next point from the light sampler, a sphere its cone sample from rng. *light is
   the chosen light's index and *pdf its density for the direction. */
static inline __attribute__((always_inline)) vec3 light_direction(struct render_ctx *ctx, vec3 o,
                                                                  struct rng *rng, int *light, double *pdf)
{
    const struct scene *sc = ctx->sc;
    int i = (int)rng_below(rng, (uint32_t)sc->n_lights);
    const struct prim *lp = &sc->prims[sc->lights[i]];
    struct pt2 s, turn = {0, 0};
    int turned = 0;
    if (ctx->lp[i].uses_points) {
        s = next_light_point(ctx, i, &turn, &turned);
    } else {
        s.x = rng_uniform32(rng);
        s.y = rng_uniform32(rng);
    }
    *light = i;
    return turned ? light_sample_turn(lp, o, s, turn.x, turn.y, pdf) : light_sample(lp, o, s, pdf);
}

/* A camera path in flight: its ray, weight, radiance so far, segments traced and its rng. */
struct path {
    ray r;
    vec3 beta, L;
    int depth;
    struct rng rng;
};

/* surface_albedo on a copy of h: h itself then stays in registers (the texture's lookup takes
   its address). */
static inline __attribute__((always_inline)) vec3
surface_albedo_copy(const struct scene *sc, const struct material *m, const struct hit *h)
{
    if (m->texture < 0)
        return m->albedo;
    struct hit copy = *h;
    return texture_albedo(sc, m, &copy);
}

/* One segment of a camera path pt whose ray's nearest hit is h (got: whether there is one): 1
   with pt's next ray set, 0 when the path ends (pt->L is then its radiance estimate). Diffuse and
   isotropic scattering draw from the mixture of the light pdf and their own (RTOW "The Rest of
   Your Life": half and half) and weight by scattering pdf / mixture pdf; mirrors and glass
   follow their one direction. Scattered directions are unit vectors. mix: the scene has lights
   sampled; last: the last segment's depth (max_depth - 1). */
static inline __attribute__((always_inline)) int shade(struct render_ctx *ctx, struct path *pt, int got,
                                                       const struct hit *h, int mix, int last)
{
    const struct scene *sc = ctx->sc;
    ray *r = &pt->r;
    struct rng *rng = &pt->rng;
    if (!got) {
        pt->L = v3_add(pt->L, v3_mul(pt->beta, sc->background));
        return 0;
    }
    const struct material *m = ctx->prim_material[h->prim];
    /* The last segment: only a light's emission counts, a scattered ray would never be
       traced (its direction, light point and pdfs are not drawn at all). */
    if (pt->depth == last && m->type != MAT_LIGHT)
        return 0;
    pt->depth++;
    vec3 dir;
    if (m->type == MAT_LAMBERTIAN) {
        vec3 albedo = surface_albedo_copy(sc, m, h);
        int light = -1;
        double light_pdf = 0;
        if (mix && rng_u32(rng) >> 31) {
            dir = light_direction(ctx, h->p, rng, &light, &light_pdf);
        } else {
            onb frame = onb_from_w(h->n);
            dir = cosine_direction_inline(&frame, rng);
        }
        /* below the surface: the scattering pdf is 0 and so is the estimate */
        double cosine = v3_dot(dir, h->n);
        if (!(cosine > 0))
            return 0;
        double cosine_pdf = cosine / PI; /* once: GCC divided again after the mixture */
        double pdf = mix ? 0.5 * lights_pdf(sc, h->p, dir, light, light_pdf) + 0.5 * cosine_pdf : cosine_pdf;
        if (!(pdf > 0))
            return 0;
        pt->beta = v3_mul(pt->beta, v3_scale(albedo, cosine_pdf / pdf));
        *r = (ray){h->p, dir, r->time};
        return 1;
    }
    switch (m->type) {
    case MAT_LIGHT:
        if (h->front)
            pt->L = v3_add(pt->L, v3_mul(pt->beta, m->emit));
        return 0;
    case MAT_METAL:
        dir = v3_fma(v3_reflect(v3_unit(r->dir), h->n), random_in_unit_sphere(rng), m->fuzz);
        if (v3_dot(dir, h->n) <= 0)
            return 0;
        pt->beta = v3_mul(pt->beta, m->albedo);
        *r = (ray){h->p, dir, r->time};
        return 1;
    case MAT_DIELECTRIC: {
        vec3 unit_dir = v3_unit(r->dir);
        double ratio = h->front ? 1.0 / m->ior : m->ior;
        double cos_t = d_min(v3_dot(v3_neg(unit_dir), h->n), 1.0);
        double sin_t = sqrt(1 - cos_t * cos_t);
        dir = (ratio * sin_t > 1 || reflectance(cos_t, ratio) > rng_uniform32(rng))
                  ? v3_reflect(unit_dir, h->n)
                  : v3_refract(unit_dir, h->n, ratio);
        *r = (ray){h->p, dir, r->time};
        return 1;
    }
    default: { /* MAT_ISOTROPIC */
        vec3 albedo = surface_albedo_copy(sc, m, h);
        const double phase = 1 / (4 * PI);
        double pdf = phase;
        if (mix) {
            int light = -1;
            double light_pdf = 0;
            dir = rng_u32(rng) >> 31 ? light_direction(ctx, h->p, rng, &light, &light_pdf)
                                     : uniform_sphere_direction(rng);
            pdf = 0.5 * shape_lights_pdf(sc, h->p, dir, light, light_pdf) + 0.5 * phase;
        } else {
            dir = uniform_sphere_direction(rng);
        }
        pt->beta = v3_mul(pt->beta, v3_scale(albedo, phase / pdf));
        *r = (ray){h->p, dir, r->time};
        return 1;
    }
    }
}

/* One camera path from r, its draws from rng; returns its radiance estimate and adds its
   segments to *rays. */
static vec3 trace(struct render_ctx *ctx, ray *r, struct rng *rng, uint64_t *rays)
{
    const int mix = ctx->sc->n_lights > 0 && !ctx->rs.light_sampling_off, last = ctx->rs.max_depth - 1;
    struct path pt = {*r, v3(1, 1, 1), v3(0, 0, 0), 0, *rng};
    for (;;) {
        struct hit h;
        ++*rays;
        int got = bvh_hit(ctx->sc, &pt.r, HIT_EPS, DBL_MAX, &h);
        if (!shade(ctx, &pt, got, &h, mix, last))
            break;
    }
    *rng = pt.rng;
    return pt.L;
}

/* Camera sample s of pixel (x, y) into path pt: its own rng, the pixel's path stream (*base)
   from a state of its own. */
static inline void path_start(struct render_ctx *ctx, struct path *pt, int x, int y, size_t s,
                              const struct rng *base)
{
    const int w = ctx->rs.width, hgt = ctx->rs.height;
    pt->rng.inc = base->inc;
    pt->rng.state = rng_mix64(base->state + s);
    struct pt2 p = ctx->pixel_pts[s];
    pt->r = camera_ray(ctx->cam, (x + p.x) / w, (hgt - y - p.y) / hgt, &pt->rng);
    pt->beta = v3(1, 1, 1);
    pt->L = v3(0, 0, 0);
    pt->depth = 0;
}

/* render_pixel's samples four paths at a time, their rays traced together (packet_hit). */
static void render_pixel_packet(struct render_ctx *ctx, int x, int y, size_t n, double sum[3], size_t *kept,
                                uint64_t *rays)
{
    struct path pt[PACKET_LANES] = {0};
    const ray *rp[PACKET_LANES];
    const int mix = ctx->sc->n_lights > 0 && !ctx->rs.light_sampling_off, last = ctx->rs.max_depth - 1;
    struct rng base;
    rng_pixel(&base, ctx->rs.seed, x, y, 2);
    int lanes = 0;
    size_t next = 0;
    for (int i = 0; i < PACKET_LANES; i++) {
        rp[i] = &pt[i].r;
        if (next < n) {
            path_start(ctx, &pt[i], x, y, next++, &base);
            lanes |= 1 << i;
        }
    }
    while (lanes) {
        struct packet_hits ph;
        int got = packet_hit(ctx->packet, rp, HIT_EPS, DBL_MAX, &ph);
        for (int m = lanes; m; m &= m - 1) {
            int i = __builtin_ctz((unsigned)m);
            ++*rays;
            struct hit h = packet_hit_of(&ph, i);
            if (shade(ctx, &pt[i], got >> i & 1, &h, mix, last))
                continue;
            vec3 c = pt[i].L;
            if (v3_finite(c)) {
                sum[0] += c.x, sum[1] += c.y, sum[2] += c.z;
                ++*kept;
            } else {
                ctx->st->nonfinite++;
            }
            if (next < n)
                path_start(ctx, &pt[i], x, y, next++, &base);
            else
                lanes &= ~(1 << i);
        }
    }
}

void render_pixel(struct render_ctx *ctx, int x, int y, float rgb[3], struct render_stats *st)
{
    struct rng pix_rng, path_rng;
    const int w = ctx->rs.width, hgt = ctx->rs.height;
    ctx->st = st;
    rng_pixel(&pix_rng, ctx->rs.seed, x, y, 0);
    rng_pixel(&ctx->light_rng, ctx->rs.seed, x, y, 1);
    rng_pixel(&path_rng, ctx->rs.seed, x, y, 2);
    for (int i = 0; i < ctx->sc->n_lights; i++)
        ctx->lp[i].n = ctx->lp[i].next = 0;

    double t0 = now_s();
    size_t n = sampler_draw(ctx->pixel, &pix_rng, ctx->pixel_pts);
    st->sampler_s += now_s() - t0;

    double sum[3] = {0, 0, 0};
    size_t kept = 0;
    uint64_t rays = 0;
    if (ctx->packet) {
        render_pixel_packet(ctx, x, y, n, sum, &kept, &rays);
    } else {
        for (size_t s = 0; s < n; s++) {
            struct pt2 p = ctx->pixel_pts[s];
            ray r = camera_ray(ctx->cam, (x + p.x) / w, (hgt - y - p.y) / hgt, &path_rng);
            vec3 c = trace(ctx, &r, &path_rng, &rays);
            if (!v3_finite(c)) {
                st->nonfinite++;
                continue;
            }
            sum[0] += c.x, sum[1] += c.y, sum[2] += c.z;
            kept++;
        }
    }
    double inv = kept ? 1.0 / kept : 0;
    for (int k = 0; k < 3; k++)
        rgb[k] = (float)(sum[k] * inv);
    st->pixels++;
    st->samples += n;
    st->rays += rays;
    if (n < st->spp_min)
        st->spp_min = (uint32_t)n;
    if (n > st->spp_max)
        st->spp_max = (uint32_t)n;
}
