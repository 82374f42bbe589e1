/* render_lanes: a pixel's camera samples four paths at a time, their rays traced together by
   packet_hit (one-node scenes, packet_usable), each path advanced by shade, trace's loop body. */
#include <float.h>

#include "base/simd.h"
#include "geom/bvh.h"
#include "geom/packet.h"
#include "render_path.h"

/* A camera path in flight: its ray, weight, radiance so far (st), its depth and its rng. */
struct path {
    struct path_state st;
    struct path_shadow shadow; /* next-event estimation's shadow ray, traced with the other lanes' */
    int depth;
    uint32_t s; /* its camera sample's index in the pixel */
    struct rng rng;
};

/* One segment of a camera path pt whose ray's nearest hit is h (got: whether there is one): 1
   with pt's next ray set, 0 when the path ends (pt->st.L is then its radiance estimate); how: the
   render's part of path_at. trace's loop body: both are path_scatter then path_survives
   (render_path.h). */
static inline __attribute__((always_inline)) int shade(struct render_ctx *ctx, struct path *pt, int got,
                                                       struct hit *h, struct path_at how, uint64_t *shadow)
{
    if (!got) {
        pt->st.L = v3_add(pt->st.L, v3_mul(pt->st.beta, ctx->sc->background));
        return 0;
    }
    /* medium_inline 0: the lanes' scenes hold no media (packet_usable) */
    const struct path_at at = {.lights = how.lights,
                               .dims = how.dims,
                               .roulette = how.roulette,
                               .last = how.last,
                               .depth = pt->depth++,
                               .sample = pt->s,
                               .shadow = &pt->shadow};
    return path_scatter(ctx, &pt->st, &pt->rng, h, shadow, at) && path_survives(ctx, &pt->st, &pt->rng, at);
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
    pt->st.r = dims ? render_camera_ray_dims(ctx, u, v, (uint32_t)s) : camera_ray(ctx->cam, u, v, &pt->rng);
    pt->s = (uint32_t)s;
    pt->st.beta = v3(1, 1, 1);
    pt->st.L = v3(0, 0, 0);
    pt->st.mis_pdf = 0;
    pt->depth = 0;
}

/* An ended lane's next camera sample, *next, if any is left of the pixel's n: 1 when pt took it. */
static inline __attribute__((always_inline)) int path_next(struct render_ctx *ctx, struct path *pt, int x,
                                                           int y, size_t n, const struct rng *base, int dims,
                                                           size_t *next)
{
    if (*next >= n)
        return 0;
    path_start(ctx, pt, x, y, (*next)++, base, dims);
    return 1;
}

/* The nearest hits of the rays *r[i] of the lanes in mask, into ph: bit i of the result set when
   lane i's ray hits. Four at a time by packet_hit, or (one lane, or no vector back-end) each
   alone by the scalar traversal: the same hits, packet_hit returns the scalar tests' answers bit
   for bit. */
static inline __attribute__((always_inline)) int
lanes_hit(const struct render_ctx *ctx, const ray *const r[PACKET_LANES], int mask, struct packet_hits *ph)
{
    if (SIMD_LANES && (mask & (mask - 1)))
        return packet_hit(ctx->packet, r, HIT_EPS, DBL_MAX, ph);
    int got = 0;
    for (int i = 0; i < PACKET_LANES; i++)
        if (mask >> i & 1)
            got |= bvh_hit_node(ctx->sc, r[i], HIT_EPS, DBL_MAX, &ph->h[i]) << i;
    return got;
}

/* render_pixel's samples four paths at a time, their rays traced together (packet_hit), into
   *ps. Inline into the two callers below, the light strategy, dims and roulette constants in the
   default's: the mixture's code holds none of theirs. */
static inline __attribute__((always_inline)) void lanes_run(struct render_ctx *ctx, int x, int y, size_t n,
                                                            const struct rng *base, struct path_at how,
                                                            struct pixel_sums *ps)
{
    struct path pt[PACKET_LANES] = {0};
    const ray *rp[PACKET_LANES], *shadow_rp[PACKET_LANES];
    double acc[3] = {0, 0, 0}; /* locals in the loop, added at the end: no stores through pointers */
    uint64_t acc_rays = 0, acc_shadow = 0, acc_nonfinite = 0;
    const int direct = how.lights == LIGHTS_NEE;
    int lanes = 0;
    size_t next = 0;
    for (int i = 0; i < PACKET_LANES; i++) {
        rp[i] = &pt[i].st.r;
        shadow_rp[i] = &pt[i].shadow.r;
        if (next < n) {
            path_start(ctx, &pt[i], x, y, next++, base, how.dims);
            lanes |= 1 << i;
        }
    }
    while (lanes) {
        struct packet_hits ph;
        int got = lanes_hit(ctx, rp, lanes, &ph), ended = 0;
        /* unrolled: each lane's path and hit record at a fixed place in the frame, no index
           arithmetic in shade's loads and stores (one copy of shade per lane) */
#pragma GCC unroll 4
        for (int i = 0; i < PACKET_LANES; i++) {
            if (!(lanes >> i & 1))
                continue;
            ++acc_rays;
            if (shade(ctx, &pt[i], got >> i & 1, &ph.h[i], how, &acc_shadow))
                continue;
            if (direct) { /* ended, once its shadow ray is traced below */
                ended |= 1 << i;
                continue;
            }
            add_estimate(pt[i].st.L, acc, &acc_nonfinite);
            if (!path_next(ctx, &pt[i], x, y, n, base, how.dims, &next))
                lanes &= ~(1 << i);
        }
        if (direct) { /* the shadow rays shade left, traced together; each adds to its path's L as it
                      would have at once (nothing else adds to L in between) */
            int pending = 0;
            for (int i = 0; i < PACKET_LANES; i++)
                pending |= pt[i].shadow.pending << i;
            if (pending) {
                int shadow_got = lanes_hit(ctx, shadow_rp, pending, &ph);
                for (int i = 0; i < PACKET_LANES; i++)
                    if (pending >> i & 1)
                        path_shadow_add(ctx, &pt[i].shadow, shadow_got >> i & 1, &ph.h[i], &pt[i].st.L);
            }
        }
        for (int i = 0; i < PACKET_LANES; i++) {
            if (!(ended >> i & 1))
                continue;
            add_estimate(pt[i].st.L, acc, &acc_nonfinite);
            if (!path_next(ctx, &pt[i], x, y, n, base, how.dims, &next))
                lanes &= ~(1 << i);
        }
    }
    for (int k = 0; k < 3; k++)
        ps->sum[k] += acc[k];
    ps->nonfinite += acc_nonfinite;
    ps->rays += acc_rays;
    ps->shadow += acc_shadow;
}

/* next-event estimation, sampler_dims: all or roulette (runtime values), out of line from the default's loop.
 */
static __attribute__((noinline)) void lanes_other(struct render_ctx *ctx, int x, int y, size_t n,
                                                  const struct rng *base, struct path_at how,
                                                  struct pixel_sums *ps)
{
    /* next-event estimation a constant in each copy: its copy holds the shadow rays' pass and none of the
       mixture's code, the other none of next-event estimation's */
    if (how.lights == LIGHTS_NEE) {
        how.lights = LIGHTS_NEE;
        lanes_run(ctx, x, y, n, base, how, ps);
    } else {
        how.lights = how.lights == LIGHTS_MIXTURE ? LIGHTS_MIXTURE : LIGHTS_NONE;
        lanes_run(ctx, x, y, n, base, how, ps);
    }
}

void render_pixel_packet(struct render_ctx *ctx, int x, int y, size_t n, const struct rng *base,
                         struct path_at how, struct pixel_sums *ps)
{
    if (how.lights == LIGHTS_NEE || how.dims || how.roulette)
        lanes_other(ctx, x, y, n, base, how, ps);
    else {
        const enum path_lights mix_or_none = how.lights == LIGHTS_MIXTURE ? LIGHTS_MIXTURE : LIGHTS_NONE;
        lanes_run(ctx, x, y, n, base, (struct path_at){.lights = mix_or_none, .last = how.last}, ps);
    }
}
