/* render: per-pixel point sets, per-light point sets consumed in order, and the mixture-pdf
   path integrator of Shirley's "Ray Tracing: The Rest of Your Life" (50% light, 50% cosine). */
#include "render.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bvh.h"
#include "shape_light_inline.h"
#include "texture.h"

/* A light's current point set within the pixel, taken in a random order, then redrawn: the
   points themselves (fresh poisson), the indices of a pool set's points, shifted when taken
   (pooled poisson), or the cells whose points are made when taken (the others). */
struct light_points {
    struct pt2 *pts;
    uint32_t *cells;
    const struct pool_point *pool; /* pooled: the set and its shift */
    double ox, oy, cos_oy, sin_oy;
    size_t n, next;
    int uses_points; /* shape_light_uses_points of the light, looked up once */
};

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
};

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

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
    into->light_sets += from->light_sets;
    into->nonfinite += from->nonfinite;
    into->sampler_s += from->sampler_s;
    if (from->spp_min < into->spp_min)
        into->spp_min = from->spp_min;
    if (from->spp_max > into->spp_max)
        into->spp_max = from->spp_max;
}

void render_ctx_free(struct render_ctx *ctx)
{
    if (!ctx)
        return;
    if (ctx->lp)
        for (int i = 0; i < ctx->sc->n_lights; i++) {
            free(ctx->lp[i].pts);
            free(ctx->lp[i].cells);
        }
    free(ctx->lp);
    free(ctx->identity);
    free(ctx->prim_material);
    free(ctx->pixel_pts);
    free(ctx);
}

struct render_ctx *render_ctx_new(const struct scene *sc, const struct camera *cam,
                                  const struct render_settings *rs, struct sampler *pixel,
                                  struct sampler *light, struct err *e)
{
    struct render_ctx *ctx = calloc(1, sizeof *ctx);
    if (!ctx)
        goto fail;
    ctx->sc = sc;
    ctx->cam = cam;
    ctx->rs = *rs;
    ctx->pixel = pixel;
    ctx->light = light;
    ctx->pixel_pts = malloc(sampler_set_capacity(pixel) * sizeof *ctx->pixel_pts);
    ctx->lp = calloc((size_t)sc->n_lights + 1, sizeof *ctx->lp);
    ctx->prim_material = malloc(((size_t)sc->n_prims + 1) * sizeof *ctx->prim_material);
    if (!ctx->pixel_pts || !ctx->lp || !ctx->prim_material)
        goto fail;
    for (int i = 0; i < sc->n_prims; i++)
        ctx->prim_material[i] = &sc->materials[sc->prims[i].material];
    if (light) {
        ctx->light_kind = sampler_kind_of(light);
        ctx->light_grid = sampler_grid_of(light);
    }
    for (int i = 0; i < sc->n_lights; i++) {
        ctx->lp[i].uses_points = shape_light_uses_points(&sc->prims[sc->lights[i]]);
        if (rs->light_sampling_off || !ctx->lp[i].uses_points)
            continue;
        if (!light) {
            err_set(e, NULL, 0, 0, "internal: scene has a disk or rect light but no light sampler");
            render_ctx_free(ctx);
            return NULL;
        }
        size_t cells = sampler_cells(light) > 0   ? sampler_cells(light)
                       : sampler_is_pooled(light) ? sampler_set_capacity(light)
                                                  : 0;
        if (cells > 0) {
            ctx->lp[i].cells = malloc(cells * sizeof *ctx->lp[i].cells);
            if (!ctx->identity) {
                ctx->identity = malloc(cells * sizeof *ctx->identity);
                if (!ctx->identity)
                    goto fail;
                for (size_t c = 0; c < cells; c++)
                    ctx->identity[c] = (uint32_t)c;
            }
        } else {
            ctx->lp[i].pts = malloc(sampler_set_capacity(light) * sizeof *ctx->lp[i].pts);
        }
        if (!ctx->lp[i].pts && !ctx->lp[i].cells)
            goto fail;
    }
    return ctx;
fail:
    render_ctx_free(ctx);
    err_set(e, NULL, 0, 0, "out of memory for the render's sample buffers");
    return NULL;
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
static vec3 cosine_direction(const onb *frame, struct rng *r)
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

/* One camera path; returns its radiance estimate and adds its segments to *rays. Diffuse and
   isotropic scattering draw from the mixture of the light pdf and their own (RTOW "The Rest of
   Your Life": half and half) and weight by scattering pdf / mixture pdf; mirrors and glass
   follow their one direction. Scattered directions are unit vectors. */
static vec3 trace(struct render_ctx *ctx, ray *r, struct rng *rng, uint64_t *rays)
{
    const struct scene *sc = ctx->sc;
    const int mix = sc->n_lights > 0 && !ctx->rs.light_sampling_off;
    vec3 L = v3(0, 0, 0), beta = v3(1, 1, 1);
    const int last = ctx->rs.max_depth - 1;
    for (int depth = 0; depth <= last; depth++) {
        struct hit h;
        ++*rays;
        if (!bvh_hit(sc, r, HIT_EPS, DBL_MAX, &h)) {
            L = v3_add(L, v3_mul(beta, sc->background));
            break;
        }
        const struct material *m = ctx->prim_material[h.prim];
        /* The last segment: only a light's emission counts, a scattered ray would never be
           traced (its direction, light point and pdfs are not drawn at all). */
        if (depth == last && m->type != MAT_LIGHT)
            return L;
        vec3 dir;
        if (m->type == MAT_LAMBERTIAN) {
            vec3 albedo = surface_albedo(sc, m, &h);
            int light = -1;
            double light_pdf = 0;
            if (mix && rng_u32(rng) >> 31) {
                dir = light_direction(ctx, h.p, rng, &light, &light_pdf);
            } else {
                onb frame = onb_from_w(h.n);
                dir = cosine_direction(&frame, rng);
            }
            /* below the surface: the scattering pdf is 0 and so is the estimate */
            double cosine = v3_dot(dir, h.n);
            if (!(cosine > 0))
                return L;
            double cosine_pdf = cosine / PI; /* once: GCC divided again after the mixture */
            double pdf =
                mix ? 0.5 * lights_pdf(sc, h.p, dir, light, light_pdf) + 0.5 * cosine_pdf : cosine_pdf;
            if (!(pdf > 0))
                return L;
            beta = v3_mul(beta, v3_scale(albedo, cosine_pdf / pdf));
            *r = (ray){h.p, dir, r->time};
            continue;
        }
        switch (m->type) {
        case MAT_LIGHT:
            if (h.front)
                L = v3_add(L, v3_mul(beta, m->emit));
            return L;
        case MAT_METAL:
            dir = v3_fma(v3_reflect(v3_unit(r->dir), h.n), random_in_unit_sphere(rng), m->fuzz);
            if (v3_dot(dir, h.n) <= 0)
                return L;
            beta = v3_mul(beta, m->albedo);
            *r = (ray){h.p, dir, r->time};
            continue;
        case MAT_DIELECTRIC: {
            vec3 unit_dir = v3_unit(r->dir);
            double ratio = h.front ? 1.0 / m->ior : m->ior;
            double cos_t = d_min(v3_dot(v3_neg(unit_dir), h.n), 1.0);
            double sin_t = sqrt(1 - cos_t * cos_t);
            dir = (ratio * sin_t > 1 || reflectance(cos_t, ratio) > rng_uniform32(rng))
                      ? v3_reflect(unit_dir, h.n)
                      : v3_refract(unit_dir, h.n, ratio);
            *r = (ray){h.p, dir, r->time};
            continue;
        }
        default: { /* MAT_ISOTROPIC */
            vec3 albedo = surface_albedo(sc, m, &h);
            const double phase = 1 / (4 * PI);
            double pdf = phase;
            if (mix) {
                int light = -1;
                double light_pdf = 0;
                dir = rng_u32(rng) >> 31 ? light_direction(ctx, h.p, rng, &light, &light_pdf)
                                         : uniform_sphere_direction(rng);
                pdf = 0.5 * shape_lights_pdf(sc, h.p, dir, light, light_pdf) + 0.5 * phase;
            } else {
                dir = uniform_sphere_direction(rng);
            }
            beta = v3_mul(beta, v3_scale(albedo, phase / pdf));
            *r = (ray){h.p, dir, r->time};
            continue;
        }
        }
    }
    return L;
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
