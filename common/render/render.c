/* render: per-pixel point sets, per-light point sets consumed in order, and the mixture-pdf
   path integrator of Shirley's "Ray Tracing: The Rest of Your Life" (50% light, 50% cosine);
   scenes that packet_usable picks trace four paths at once through vector hit tests
   (render_lanes.c) that return the scalar tests' answers bit for bit. */
#include "render.h"

#include <float.h>

#include "geom/bvh.h"
#include "render_path.h"

/* One camera path; returns its radiance estimate and adds its segments to *rays. Diffuse and
   isotropic scattering draw from the mixture of the light pdf and their own (RTOW "The Rest of
   Your Life": half and half) and weight by scattering pdf / mixture pdf; mirrors and glass
   follow their one direction. Scattered directions are unit vectors. Each segment's
   interaction is path_scatter (render_path.h), which the packet's lanes (render_lanes.c) share,
   then Russian roulette (path_survives) when path.roulette; inline, with mix and last made once
   per pixel. path: the camera sample's decisions (its depth is the loop's). */
static inline __attribute__((always_inline)) vec3 trace(struct render_ctx *ctx, ray *r, struct rng *rng,
                                                        uint64_t *rays, int mix, int nee, struct path_at path,
                                                        int last)
{
    const struct scene *sc = ctx->sc;
    vec3 L = v3(0, 0, 0), beta = v3(1, 1, 1);
    double mis_pdf = 0;
    for (int depth = 0; depth <= last; depth++) {
        struct hit h;
        ++*rays;
        if (!bvh_hit(sc, r, HIT_EPS, DBL_MAX, &h)) {
            L = v3_add(L, v3_mul(beta, sc->background));
            break;
        }
        const struct path_at at = {path.dims, depth, path.sample, path.roulette, NULL};
        if (!path_scatter_as(ctx, r, &beta, &L, rng, &h, depth == last, mix, nee, &mis_pdf, rays, at, 1) ||
            !path_survives(ctx, &beta, rng, at))
            break;
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
    for (int i = 0; i < ctx->sc->n_lights; i++) {
        stream_restart(&ctx->lp[i]);
        /* halton, zsobol: light i's sets in this pixel are dimensions of their own (sampler_at) */
        ctx->lp[i].at = (struct sampler_at){ctx->rs.seed, x, y, STREAM_LIGHT_DIM + ((uint32_t)i << 16)};
    }

    const int timed = ctx->timed = sampler_timed(st->pixels);
    ctx->light_source.sets = &st->light_sets;
    ctx->light_source.timed_draw_ns = timed ? &st->timed_draw_ns : NULL;
    const uint64_t t0 = timed ? now_ns() : 0;
    const struct sampler_at at = {ctx->rs.seed, x, y, 0};
    size_t n = sampler_draw_at(ctx->pixel, &pix_rng, &at, ctx->pixel_pts);
    if (timed)
        st->timed_draw_ns += now_ns() - t0;

    double sum[3] = {0, 0, 0};
    uint64_t rays = 0, nonfinite = 0;
    /* nee samples the emitters alone: without any, only the material's own sampling is left */
    const int lights = !ctx->rs.light_sampling_off, last = ctx->rs.max_depth - 1;
    const int nee = lights && ctx->rs.nee && ctx->sc->n_emitters > 0;
    const int mix = lights && !ctx->rs.nee && ctx->sc->n_lights > 0, dims = ctx->rs.dims_all;
    const int rr = ctx->rs.russian_roulette;
    if (dims) {
        padding_pixel(&ctx->pad, ctx->rs.seed, x, y, n);
        ctx->pad.timed_draw_ns = timed ? &st->timed_draw_ns : NULL;
    }
    if (ctx->packet) {
        const struct path_at how = {dims, 0, 0, rr, NULL};
        render_pixel_packet(ctx, x, y, n, &path_rng, mix, nee, how, last, sum, &nonfinite, &rays);
    } else {
        /* nee, dims and roulette constants in the default loop: the mixture's inlined trace holds
           none of their code */
        for (size_t s = 0; s < n; s++) {
            struct pt2 p = ctx->pixel_pts[s];
            const double u = (x + p.x) / w, v = (hgt - y - p.y) / hgt;
            vec3 c;
            if (nee || dims || rr) {
                ray r = dims ? render_camera_ray_dims(ctx, u, v, (uint32_t)s)
                             : camera_ray(ctx->cam, u, v, &path_rng);
                const struct path_at path = {dims, 0, (uint32_t)s, rr, NULL};
                c = trace(ctx, &r, &path_rng, &rays, mix, nee, path, last);
            } else {
                ray r = camera_ray(ctx->cam, u, v, &path_rng);
                c = trace(ctx, &r, &path_rng, &rays, mix, 0, (struct path_at){0, 0, 0, 0, NULL}, last);
            }
            add_estimate(c, sum, &nonfinite);
        }
    }
    double inv = n ? 1.0 / n : 0; /* non-finite samples count as zero */
    for (int k = 0; k < 3; k++)
        rgb[k] = (float)(sum[k] * inv);
    if (timed)
        st->timed_pixel_ns += now_ns() - t0;
    st->pixels++;
    st->samples += n;
    st->rays += rays;
    st->nonfinite += nonfinite;
    if (n < st->spp_min)
        st->spp_min = (uint32_t)n;
    if (n > st->spp_max)
        st->spp_max = (uint32_t)n;
}
