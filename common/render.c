/* render: per-pixel point sets, per-light point sets consumed in order, and the mixture-pdf
   path integrator of Shirley's "Ray Tracing: The Rest of Your Life" (50% light, 50% cosine);
   scenes that packet_usable picks trace four paths at once (render_lanes.c). */
#include "render.h"

#include <float.h>

#include "bvh.h"
#include "render_path.h"

/* One camera path; returns its radiance estimate and adds its segments to *rays. Diffuse and
   isotropic scattering draw from the mixture of the light pdf and their own (RTOW "The Rest of
   Your Life": half and half) and weight by scattering pdf / mixture pdf; mirrors and glass
   follow their one direction. Scattered directions are unit vectors. render_lanes.c's shade
   does one iteration of this loop for the packet's lanes: keep the two alike. */
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
