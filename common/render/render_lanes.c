/* render_lanes: a pixel's camera samples four paths at a time, their rays traced together by
   packet_hit (one-node scenes, packet_usable), each path advanced by shade, trace's loop body. */
#include <float.h>

#include "base/simd.h"
#include "geom/bvh.h"
#include "geom/packet.h"
#include "render_path.h"

/* A camera path in flight: its ray, weight, radiance so far, segments traced and its rng. */
struct path {
    ray r;
    vec3 beta, L;
    double mis_pdf; /* next-event estimation's: the last scatter's pdf (path_scatter_as) */
    int depth;
    uint32_t s; /* its camera sample's index in the pixel */
    struct rng rng;
};

/* One segment of a camera path pt whose ray's nearest hit is h (got: whether there is one): 1
   with pt's next ray set, 0 when the path ends (pt->L is then its radiance estimate); mix: the
   scene has lights sampled (nee: by next-event estimation); how: sampler_dims: all (dims) and
   Russian roulette (roulette); last: the last segment's depth (max_depth - 1). trace's loop body:
   both are path_scatter then path_survives (render_path.h). */
static inline __attribute__((always_inline)) int shade(struct render_ctx *ctx, struct path *pt, int got,
                                                       struct hit *h, int mix, int nee, struct path_at how,
                                                       int last, uint64_t *rays)
{
    if (!got) {
        pt->L = v3_add(pt->L, v3_mul(pt->beta, ctx->sc->background));
        return 0;
    }
    const struct path_at at = {how.dims, pt->depth, pt->s, how.roulette};
    return path_scatter(ctx, &pt->r, &pt->beta, &pt->L, &pt->rng, h, pt->depth++ == last, mix, nee,
                        &pt->mis_pdf, rays, at) &&
           path_survives(ctx, &pt->beta, &pt->rng, at);
}

/* Camera sample s of pixel (x, y) into path pt, with an rng of its own: the pixel's path
   stream (*base) from the state rng_mix64(state + s), so that a sample's own draws do not depend
   on which lane runs it or when (64 starts spread over the 2^64-long sequence, a few hundred
   draws each: the chance of an overlap is below 2^-40). Its light points do: they come from the
   pixel's shared sets (ctx->lp, ctx->light_rng), taken in the order the lanes ask for them. That
   order is fixed by the pixel's own work, so a pixel still depends only on seed and pixel. */
static inline __attribute__((always_inline)) void
path_start(struct render_ctx *ctx, struct path *pt, int x, int y, size_t s, const struct rng *base, int dims)
{
    const int w = ctx->rs.width, hgt = ctx->rs.height;
    pt->rng.inc = base->inc;
    pt->rng.state = rng_mix64(base->state + s);
    struct pt2 p = ctx->pixel_pts[s];
    const double u = (x + p.x) / w, v = (hgt - y - p.y) / hgt;
    pt->r = dims ? render_camera_ray_dims(ctx, u, v, (uint32_t)s) : camera_ray(ctx->cam, u, v, &pt->rng);
    pt->s = (uint32_t)s;
    pt->beta = v3(1, 1, 1);
    pt->L = v3(0, 0, 0);
    pt->mis_pdf = 0;
    pt->depth = 0;
}

/* render_pixel's samples four paths at a time, their rays traced together (packet_hit). Inline
   into the two callers below, nee, dims and roulette constants in the default's: the mixture's
   code holds none of theirs. */
static inline __attribute__((always_inline)) void lanes_run(struct render_ctx *ctx, int x, int y, size_t n,
                                                            const struct rng *base, int mix, int nee,
                                                            struct path_at how, int last, double sum[3],
                                                            size_t *kept, uint64_t *nonfinite, uint64_t *rays)
{
    struct path pt[PACKET_LANES] = {0};
    const ray *rp[PACKET_LANES];
    double acc[3] = {0, 0, 0}; /* locals in the loop, added at the end: no stores through pointers */
    size_t acc_kept = 0;
    uint64_t acc_rays = 0, acc_nonfinite = 0;
    int lanes = 0;
    size_t next = 0;
    for (int i = 0; i < PACKET_LANES; i++) {
        rp[i] = &pt[i].r;
        if (next < n) {
            path_start(ctx, &pt[i], x, y, next++, base, how.dims);
            lanes |= 1 << i;
        }
    }
    while (lanes) {
        struct packet_hits ph;
        int got;
        if (SIMD_LANES && (lanes & (lanes - 1))) {
            got = packet_hit(ctx->packet, rp, HIT_EPS, DBL_MAX, &ph);
        } else { /* one lane left, or no vector back-end: each ray alone by the scalar traversal
                    (the same hits: packet_hit returns the scalar tests' answers bit for bit) */
            got = 0;
            for (int i = 0; i < PACKET_LANES; i++)
                if (lanes >> i & 1)
                    got |= bvh_hit_node(ctx->sc, rp[i], HIT_EPS, DBL_MAX, &ph.h[i]) << i;
        }
        /* unrolled: each lane's path and hit record at a fixed place in the frame, no index
           arithmetic in shade's loads and stores (one copy of shade per lane) */
#pragma GCC unroll 4
        for (int i = 0; i < PACKET_LANES; i++) {
            if (!(lanes >> i & 1))
                continue;
            ++acc_rays;
            if (shade(ctx, &pt[i], got >> i & 1, &ph.h[i], mix, nee, how, last, &acc_rays))
                continue;
            add_estimate(pt[i].L, acc, &acc_kept, &acc_nonfinite);
            if (next < n)
                path_start(ctx, &pt[i], x, y, next++, base, how.dims);
            else
                lanes &= ~(1 << i);
        }
    }
    for (int k = 0; k < 3; k++)
        sum[k] += acc[k];
    *kept += acc_kept;
    *nonfinite += acc_nonfinite;
    *rays += acc_rays;
}

/* nee, sampler_dims: all or roulette (runtime values), out of line from the default's loop. */
static __attribute__((noinline)) void lanes_other(struct render_ctx *ctx, int x, int y, size_t n,
                                                  const struct rng *base, int mix, int nee,
                                                  struct path_at how, int last, double sum[3], size_t *kept,
                                                  uint64_t *nonfinite, uint64_t *rays)
{
    lanes_run(ctx, x, y, n, base, mix, nee, how, last, sum, kept, nonfinite, rays);
}

void render_pixel_packet(struct render_ctx *ctx, int x, int y, size_t n, const struct rng *base, int mix,
                         int nee, struct path_at how, int last, double sum[3], size_t *kept,
                         uint64_t *nonfinite, uint64_t *rays)
{
    if (nee || how.dims || how.roulette)
        lanes_other(ctx, x, y, n, base, mix, nee, how, last, sum, kept, nonfinite, rays);
    else
        lanes_run(ctx, x, y, n, base, mix, 0, (struct path_at){0, 0, 0, 0}, last, sum, kept, nonfinite, rays);
}
