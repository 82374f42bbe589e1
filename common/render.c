/* render: per-pixel point sets, per-light point sets consumed in order, and the mixture-pdf
   path integrator of Shirley's "Ray Tracing: The Rest of Your Life" (50% light, 50% cosine). */
#include "render.h"

#include <float.h>
#include <stdlib.h>
#include <time.h>

#include "bvh.h"
#include "texture.h"

/* A light's current point set within the pixel: points are used in order, then redrawn. */
struct light_points {
    struct pt2 *pts;
    size_t n, next;
};

struct render_ctx {
    const struct scene *sc;
    const struct camera *cam;
    struct render_settings rs;
    struct sampler *pixel, *light;
    struct pt2 *pixel_pts;
    struct light_points *lp; /* one per scene light */
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
        for (int i = 0; i < ctx->sc->n_lights; i++)
            free(ctx->lp[i].pts);
    free(ctx->lp);
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
    if (!ctx->pixel_pts || !ctx->lp)
        goto fail;
    for (int i = 0; i < sc->n_lights; i++) {
        if (rs->light_sampling_off || !shape_light_uses_points(&sc->prims[sc->lights[i]]))
            continue;
        if (!light) {
            err_set(e, NULL, 0, 0, "internal: scene has a disk or rect light but no light sampler");
            render_ctx_free(ctx);
            return NULL;
        }
        ctx->lp[i].pts = malloc(sampler_set_capacity(light) * sizeof *ctx->lp[i].pts);
        if (!ctx->lp[i].pts)
            goto fail;
    }
    return ctx;
fail:
    render_ctx_free(ctx);
    err_set(e, NULL, 0, 0, "out of memory for the render's sample buffers");
    return NULL;
}

/* Next point of light i's current set, drawing a fresh set when it runs out. A pixel uses
   only part of a set, in order; a grid or Poisson set in generation order would then cover
   only part of the light (a grid's first rows, a Poisson blob around its first point) and
   bias the image, so the set is consumed in a random order: a Fisher-Yates shuffle done lazily,
   one swap per point taken. Every point consumed is then uniform over the light, and the set
   still stratifies what is consumed of it. */
static struct pt2 next_light_point(struct render_ctx *ctx, int i)
{
    struct light_points *lp = &ctx->lp[i];
    if (lp->next >= lp->n) {
        double t0 = now_s();
        lp->n = sampler_draw(ctx->light, &ctx->light_rng, lp->pts);
        lp->next = 0;
        ctx->st->sampler_s += now_s() - t0;
        ctx->st->light_sets++;
    }
    size_t k = lp->next++;
    size_t j = k + rng_below(&ctx->light_rng, (uint32_t)(lp->n - k));
    struct pt2 chosen = lp->pts[j];
    lp->pts[j] = lp->pts[k];
    lp->pts[k] = chosen;
    return chosen;
}

static double light_pdf(const struct scene *sc, vec3 o, vec3 dir, double time)
{
    double sum = 0;
    for (int i = 0; i < sc->n_lights; i++)
        sum += shape_light_pdf(&sc->prims[sc->lights[i]], o, dir, time);
    return sum / sc->n_lights;
}

static vec3 random_in_unit_sphere(struct rng *r)
{
    for (;;) {
        vec3 p = v3(2 * rng_uniform(r) - 1, 2 * rng_uniform(r) - 1, 2 * rng_uniform(r) - 1);
        if (v3_len2(p) < 1)
            return p;
    }
}

/* Cosine-weighted direction about n (Malley's method). */
static vec3 cosine_direction(const onb *frame, struct rng *r)
{
    double u1 = rng_uniform(r), u2 = rng_uniform(r);
    double phi = 2 * PI * u1, s = sqrt(u2);
    return onb_local(frame, v3(cos(phi) * s, sin(phi) * s, sqrt(1 - u2)));
}

static vec3 uniform_sphere_direction(struct rng *r)
{
    double z = 1 - 2 * rng_uniform(r), phi = 2 * PI * rng_uniform(r), s = sqrt(fmax(0, 1 - z * z));
    return v3(cos(phi) * s, sin(phi) * s, z);
}

static vec3 surface_albedo(const struct scene *sc, const struct material *m, struct hit *h)
{
    if (m->texture < 0)
        return m->albedo;
    const struct texture *t = &sc->textures[m->texture];
    if (texture_needs_uv(t))
        shape_uv(&sc->prims[h->prim], h);
    return texture_value(sc, t, h->u, h->v, h->p);
}

static double reflectance(double cosine, double ref_idx)
{
    /* Schlick's approximation. */
    double r0 = (1 - ref_idx) / (1 + ref_idx);
    r0 *= r0;
    return r0 + (1 - r0) * pow(1 - cosine, 5);
}

/* A direction toward one of the scene's lights, chosen uniformly; disk and rect lights take
   their next point from the light sampler, a sphere its cone sample from rng. */
static vec3 light_direction(struct render_ctx *ctx, vec3 o, struct rng *rng)
{
    const struct scene *sc = ctx->sc;
    int i = (int)rng_below(rng, (uint32_t)sc->n_lights);
    const struct prim *lp = &sc->prims[sc->lights[i]];
    struct pt2 s;
    if (shape_light_uses_points(lp)) {
        s = next_light_point(ctx, i);
    } else {
        s.x = rng_uniform(rng);
        s.y = rng_uniform(rng);
    }
    return shape_light_dir(lp, o, s);
}

/* One camera path; returns its radiance estimate. Diffuse and isotropic scattering draw from
   the mixture of the light pdf and their own (RTOW "The Rest of Your Life": half and half) and
   weight by scattering pdf / mixture pdf; mirrors and glass follow their one direction. */
static vec3 trace(struct render_ctx *ctx, ray r, struct rng *rng)
{
    const struct scene *sc = ctx->sc;
    const int mix = sc->n_lights > 0 && !ctx->rs.light_sampling_off;
    vec3 L = v3(0, 0, 0), beta = v3(1, 1, 1);
    for (int depth = 0; depth < ctx->rs.max_depth; depth++) {
        struct hit h;
        ctx->st->rays++;
        if (!bvh_hit(sc, &r, HIT_EPS, DBL_MAX, &h)) {
            L = v3_add(L, v3_mul(beta, sc->background));
            break;
        }
        const struct material *m = &sc->materials[sc->prims[h.prim].material];
        vec3 unit_dir = v3_unit(r.dir), dir;
        switch (m->type) {
        case MAT_LIGHT:
            if (h.front)
                L = v3_add(L, v3_mul(beta, m->emit));
            return L;
        case MAT_METAL:
            dir = v3_fma(v3_reflect(unit_dir, h.n), random_in_unit_sphere(rng), m->fuzz);
            if (v3_dot(dir, h.n) <= 0)
                return L;
            beta = v3_mul(beta, m->albedo);
            r = (ray){h.p, dir, r.time};
            continue;
        case MAT_DIELECTRIC: {
            double ratio = h.front ? 1.0 / m->ior : m->ior;
            double cos_t = fmin(v3_dot(v3_neg(unit_dir), h.n), 1.0);
            double sin_t = sqrt(1 - cos_t * cos_t);
            dir = (ratio * sin_t > 1 || reflectance(cos_t, ratio) > rng_uniform(rng))
                      ? v3_reflect(unit_dir, h.n)
                      : v3_refract(unit_dir, h.n, ratio);
            r = (ray){h.p, dir, r.time};
            continue;
        }
        case MAT_ISOTROPIC: {
            vec3 albedo = surface_albedo(sc, m, &h);
            const double phase = 1 / (4 * PI);
            double pdf = phase;
            if (mix) {
                dir = rng_uniform(rng) < 0.5 ? light_direction(ctx, h.p, rng) : uniform_sphere_direction(rng);
                pdf = 0.5 * light_pdf(sc, h.p, dir, r.time) + 0.5 * phase;
            } else {
                dir = uniform_sphere_direction(rng);
            }
            beta = v3_mul(beta, v3_scale(albedo, phase / pdf));
            r = (ray){h.p, dir, r.time};
            continue;
        }
        default: {
            vec3 albedo = surface_albedo(sc, m, &h);
            onb frame = onb_from_w(h.n);
            double pdf;
            if (mix) {
                dir = rng_uniform(rng) < 0.5 ? light_direction(ctx, h.p, rng) : cosine_direction(&frame, rng);
                double c = v3_dot(v3_unit(dir), h.n);
                pdf = 0.5 * light_pdf(sc, h.p, dir, r.time) + 0.5 * (c > 0 ? c / PI : 0);
            } else {
                dir = cosine_direction(&frame, rng);
                pdf = fmax(0, v3_dot(v3_unit(dir), h.n)) / PI;
            }
            double cosine = v3_dot(v3_unit(dir), h.n);
            if (cosine <= 0 || !(pdf > 0))
                return L;
            beta = v3_mul(beta, v3_scale(albedo, (cosine / PI) / pdf));
            r = (ray){h.p, dir, r.time};
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
    for (size_t s = 0; s < n; s++) {
        struct pt2 p = ctx->pixel_pts[s];
        ray r = camera_ray(ctx->cam, (x + p.x) / w, (hgt - y - p.y) / hgt, &path_rng);
        vec3 c = trace(ctx, r, &path_rng);
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
    if (n < st->spp_min)
        st->spp_min = (uint32_t)n;
    if (n > st->spp_max)
        st->spp_max = (uint32_t)n;
}
