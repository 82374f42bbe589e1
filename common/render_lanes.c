/* render_lanes: a pixel's camera samples four paths at a time, their rays traced together by
   packet_hit (one-node scenes, packet_usable), each path advanced by shade, trace's loop body. */
#include <float.h>

#include "packet.h"
#include "render_path.h"

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
   with pt's next ray set, 0 when the path ends (pt->L is then its radiance estimate); mix: the
   scene has lights sampled; last: the last segment's depth (max_depth - 1). The same steps, in
   the same order, as an iteration of render.c's trace loop (keep the two alike): trace keeps
   its own copy because written as a loop over shade it cost the scenes that do not use the
   packet 1-2% (final 249.6 -> 254.7 ns, cornell-pool 193.0 -> 195.0). */
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

/* Camera sample s of pixel (x, y) into path pt, with an rng of its own: the pixel's path
   stream (*base) from the state rng_mix64(state + s), so that a sample's draws do not depend on
   which lane runs it or when (64 starts spread over the 2^64-long sequence, a few hundred draws
   each: the chance of an overlap is below 2^-40). */
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
void render_pixel_packet(struct render_ctx *ctx, int x, int y, size_t n, double sum_out[3], size_t *kept_out,
                         uint64_t *rays_out)
{
    double sum[3] = {0, 0, 0};
    size_t kept = 0;
    uint64_t rays = 0, nonfinite = 0;
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
            ++rays;
            struct hit h = packet_hit_of(&ph, i);
            if (shade(ctx, &pt[i], got >> i & 1, &h, mix, last))
                continue;
            vec3 c = pt[i].L;
            if (v3_finite(c)) {
                sum[0] += c.x, sum[1] += c.y, sum[2] += c.z;
                ++kept;
            } else {
                nonfinite++;
            }
            if (next < n)
                path_start(ctx, &pt[i], x, y, next++, &base);
            else
                lanes &= ~(1 << i);
        }
    }
    for (int k = 0; k < 3; k++)
        sum_out[k] += sum[k];
    *kept_out += kept;
    *rays_out += rays;
    ctx->st->nonfinite += nonfinite;
}
