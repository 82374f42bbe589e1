/* render: per-pixel point sets, per-light point sets consumed in order, and the mixture-pdf
   path integrator of Shirley's "Ray Tracing: The Rest of Your Life" (50% light, 50% cosine);
   scenes that packet_usable picks trace four paths at once through vector hit tests
   (render_lanes.c) that return the scalar tests' answers bit for bit. */
#include "render.h"

#include <float.h>

#include "geom/bvh.h"
#include "render_path.h"

/* One camera path from the ray r; returns its radiance estimate and adds its segments to *rays,
   its shadow rays to *shadow.
   Diffuse and isotropic scattering draw from the mixture of the light pdf and their own (RTOW
   "The Rest of Your Life": half and half) and weight by scattering pdf / mixture pdf; mirrors and
   glass follow their one direction. Scattered directions are unit vectors. Each segment's
   interaction is path_scatter (render_path.h), which the packet's lanes (render_lanes.c) share,
   then Russian roulette (path_survives) when how.roulette; inline, with the light strategy and
   last made once per pixel. how: the render's part of path_at and the camera sample's index. */
static inline __attribute__((always_inline)) vec3 trace(struct render_ctx *ctx, ray r, struct rng *rng,
                                                        uint64_t *rays, uint64_t *shadow, struct path_at how)
{
    const struct scene *sc = ctx->sc;
    struct path_state p = {r, v3(1, 1, 1), v3(0, 0, 0), 0};
    for (int depth = 0; depth <= how.last; depth++) {
        struct hit h;
        ++*rays;
        if (!bvh_hit(sc, &p.r, HIT_EPS, DBL_MAX, &h)) {
            p.L = v3_add(p.L, v3_mul(p.beta, sc->background));
            break;
        }
        struct path_at at = how;
        at.depth = depth;
        if (!path_scatter(ctx, &p, rng, &h, shadow, at) || !path_survives(ctx, &p, rng, at))
            break;
    }
    return p.L;
}

size_t render_pixel_paths(struct render_ctx *ctx, int x, int y, size_t max_paths, float rgb[3],
                          struct render_stats *st)
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
    const uint64_t t0 = timed ? clock_ns(CLOCK_MONOTONIC) : 0;
    const struct sampler_at at = {ctx->rs.seed, x, y, 0};
    const size_t drawn = sampler_draw_at(ctx->pixel, &pix_rng, &at, ctx->pixel_pts);
    const size_t n = drawn < max_paths ? drawn : max_paths; /* the first n of the pixel's samples */
    if (timed)
        st->timed_draw_ns += clock_ns(CLOCK_MONOTONIC) - t0;

    struct pixel_sums ps = {{0, 0, 0}, 0, 0, 0};
    ctx->light_points = ctx->padded_points = 0;
    /* next-event estimation samples the emitters alone: without any, only the material's own sampling is left
     */
    const int lights = !ctx->rs.light_sampling_off, last = ctx->rs.max_depth - 1;
    const int direct = lights && ctx->rs.integrator == INTEGRATOR_NEE && ctx->sc->n_emitters > 0;
    const int mix = lights && ctx->rs.integrator == INTEGRATOR_MIXTURE && ctx->sc->n_lights > 0,
              dims = ctx->rs.dims_all;
    const int rr = ctx->rs.russian_roulette;
    /* the mixture or none: a runtime value in the default loops, in which direct is a constant 0 */
    const enum path_lights mix_or_none = mix ? LIGHTS_MIXTURE : LIGHTS_NONE;
    if (dims) {
        padding_pixel(&ctx->pad, ctx->rs.seed, x, y, n);
        ctx->pad.timed_draw_ns = timed ? &st->timed_draw_ns : NULL;
    }
    if (ctx->packet) {
        const struct path_at how = {
            .lights = direct ? LIGHTS_NEE : mix_or_none, .dims = dims, .roulette = rr, .last = last};
        render_pixel_packet(ctx, x, y, n, &path_rng, how, &ps);
    } else {
        /* direct, dims and roulette constants in the default loop: the mixture's inlined trace holds
           none of their code */
        for (size_t s = 0; s < n; s++) {
            struct pt2 p = ctx->pixel_pts[s];
            const double u = (x + p.x) / w, v = (hgt - y - p.y) / hgt;
            vec3 c;
            if (direct || dims || rr) {
                ray r = dims ? render_camera_ray_dims(ctx, u, v, (uint32_t)s)
                             : camera_ray(ctx->cam, u, v, &path_rng);
                const struct path_at how = {.lights = direct ? LIGHTS_NEE : mix_or_none,
                                            .dims = dims,
                                            .roulette = rr,
                                            .last = last,
                                            .medium_inline = 1,
                                            .sample = (uint32_t)s};
                c = trace(ctx, r, &path_rng, &ps.rays, &ps.shadow, how);
            } else {
                const struct path_at how = {.lights = mix_or_none, .last = last, .medium_inline = 1};
                c = trace(ctx, camera_ray(ctx->cam, u, v, &path_rng), &path_rng, &ps.rays, &ps.shadow, how);
            }
            add_estimate(c, ps.sum, &ps.nonfinite);
        }
    }
    double inv = n ? 1.0 / n : 0; /* non-finite samples count as zero */
    for (int k = 0; k < 3; k++)
        rgb[k] = (float)(ps.sum[k] * inv);
    if (timed)
        st->timed_pixel_ns += clock_ns(CLOCK_MONOTONIC) - t0;
    st->pixels++;
    st->samples += n;
    st->rays += ps.rays + ps.shadow;
    st->shadow_rays += ps.shadow;
    st->pixel_points += drawn;
    st->light_points += ctx->light_points;
    st->padded_points += ctx->padded_points;
    if (dims) /* the slots this pixel's samples reached, each drawn once */
        for (int k = 0; k < ctx->pad.slots; k++)
            st->padded_sets += ctx->pad.gen[k] == ctx->pad.pixel;
    st->nonfinite += ps.nonfinite;
    if (n < st->spp_min)
        st->spp_min = (uint32_t)n;
    if (n > st->spp_max)
        st->spp_max = (uint32_t)n;
    return drawn;
}

void render_pixel(struct render_ctx *ctx, int x, int y, float rgb[3], struct render_stats *st)
{
    render_pixel_paths(ctx, x, y, SIZE_MAX, rgb, st);
}
