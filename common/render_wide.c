/* render_wide: a pixel's camera paths eight at a time, their state by component in float lanes
   from the camera to the estimate (render_wide.h): the hit (wide_scene.h), the light or the
   background met, a diffuse bounce with the light mixture, a dielectric's reflection or
   refraction, all lanes at once under masks. Only the rect lights' points are taken lane by lane
   (in lane order from the pixel's shared sets), and a lane's start and its estimate's sum. */
#include "render_wide.h"

#if WIDE_KERNEL
#include <float.h>

#include "bvh.h"
#include "render_path.h"
#include "wide_scene.h"

/* A pixel's last paths go on in the scalar integrator once this few are left (lane_finish). */
#ifndef WIDE_FINISH_LANES
#define WIDE_FINISH_LANES 2
#endif

/* The paths in flight: ray, weight, segments traced, rng state, by component. */
struct lanes {
    f8 o[3], d[3], beta[3];
    i8 depth;
    struct rng8 rng;
};

/* Camera sample s of pixel (x, y) into lane i, its rng as path_start's (render_lanes.c). */
static WAI void lane_start(struct render_ctx *ctx, struct lanes *ln, int i, int x, int y, size_t s,
                           const struct rng *base)
{
    const int w = ctx->rs.width, hgt = ctx->rs.height;
    struct rng r = {rng_mix64(base->state + s), base->inc};
    const struct pt2 p = ctx->pixel_pts[s];
    ray cr = camera_ray(ctx->cam, (x + p.x) / w, (hgt - y - p.y) / hgt, &r);
    /* an eye far from the scene: the ray starts (in double) a ball's radius and t_min before the
       ball that holds every prim, so its float origin and hits round at the scene's scale, not
       the eye's (from 1e5 away its hits were 0.008 off: bounces began inside the box, whose face
       came out at half its brightness) */
    const struct wide_scene *ws = ctx->wide;
    const vec3 to_c = v3_sub(v3(ws->centre[0], ws->centre[1], ws->centre[2]), cr.orig);
    /* only for an eye beyond 8 radii: nearer, the offset's |o| term is enough, and most camera
       rays pay no square root (cornell-book3's eye is 2.2 radii away) */
    if (v3_len2(to_c) > 64 * ws->radius * ws->radius) {
        const double len = v3_len(cr.dir),
                     ahead = v3_dot(to_c, cr.dir) / len - 2 * ws->radius - HIT_EPS * len;
        if (ahead > 0)
            cr.orig = v3_fma(cr.orig, cr.dir, ahead / len);
    }
    for (int j = 0; j < 3; j++)
        ln->o[j][i] = (float)(v3_get(cr.orig, j) - ws->centre[j]);
    ln->d[0][i] = (float)cr.dir.x, ln->d[1][i] = (float)cr.dir.y, ln->d[2][i] = (float)cr.dir.z;
    ln->beta[0][i] = ln->beta[1][i] = ln->beta[2][i] = 1;
    ln->depth[i] = 0;
    if (i < 4)
        ln->rng.lo[i] = r.state;
    else
        ln->rng.hi[i - 4] = r.state;
}

/* A sphere light's cone from the lanes' points p: centre minus p, its length^2, 1 - cos of the
   half-angle (2 inside: sphere_one_minus_cos). */
struct cone {
    f8 to_c[3], d2, omc;
    i8 inside;
};

static WAI void cone_of(const struct wide_light *l, const f8 p[3], struct cone *c)
{
    for (int j = 0; j < 3; j++)
        c->to_c[j] = l->c[j] - p[j];
    c->d2 = dot8(c->to_c, c->to_c);
    c->inside = c->d2 <= l->r2;
    const f8 s2 = l->r2 / c->d2;
    c->omc = pick(c->inside, f8s(2), s2 / (1 + wsqrt(1 - s2)));
}

static WAI f8 lights_mean8(f8 sum, int n)
{
    return n == 1 ? sum : n == 2 ? sum * 0.5f : sum / (float)n;
}

/* sphere_pdf for directions dir */
static WAI f8 sphere_pdf8(const struct wide_light *l, const struct cone *c, const f8 dir[3])
{
    const f8 dc = dot8(dir, c->to_c);
    const i8 in = dc * f8_abs(dc) >= (c->d2 - l->r2) * dot8(dir, dir);
    const f8 pdf = pick(in, 1 / ((float)(2 * PI) * c->omc), f8s(0));
    return pick(c->inside, f8s((float)(1 / (4 * PI))), pdf);
}

/* rect_pdf_hit (its cone test is a shortcut only: it never rejects what this accepts) */
static WAI f8 rect_pdf8(const struct wide_light *l, const f8 p[3], const f8 dir[3])
{
    const f8 dn = dir[l->on], t = (l->k - p[l->on]) / dn;
    const f8 qa = p[l->oa] + dir[l->oa] * t, qb = p[l->ob] + dir[l->ob] * t;
    const f8 dd = dot8(dir, dir), sd = wsqrt(dd), adn = f8_abs(dn);
    i8 ok = (t > (float)HIT_EPS) & (t < FLT_MAX) & (adn > 1e-12f * sd);
    ok &= ~((qa < l->a0) | (qa > l->a1) | (qb < l->b0) | (qb > l->b1));
    return pick(ok, t * t * dd * sd / (adn * l->area), f8s(0));
}

/* The rect light l's point for each lane of `chose` (the pixel's set, lanes in order), the
   direction to it from p and its pdf (planar_sample), into dir and pdf on those lanes. */
static WAI void rect_sample8(struct render_ctx *ctx, int li, const struct wide_light *l, int chose,
                             const f8 p[3], f8 dir[3], f8 *pdf)
{
    f8 sx = f8s(0), sy = f8s(0);
    for (int b = chose; b; b &= b - 1) {
        const int i = __builtin_ctz((unsigned)b);
        struct pt2 turn;
        int turned = 0;
        const struct pt2 s = next_light_point(ctx, li, &turn, &turned);
        sx[i] = (float)s.x, sy[i] = (float)s.y;
    }
    f8 to_q[3];
    to_q[l->on] = l->k - p[l->on];
    to_q[l->oa] = (l->a0 + sx * (l->a1 - l->a0)) - p[l->oa];
    to_q[l->ob] = (l->b0 + sy * (l->b1 - l->b0)) - p[l->ob];
    const f8 len2 = dot8(to_q, to_q), len = wsqrt(len2), inv = 1.0f / len, qn = f8_abs(to_q[l->on]);
    const i8 m = lane_mask(chose);
    for (int j = 0; j < 3; j++)
        dir[j] = pick(m, to_q[j] * inv, dir[j]);
    const i8 ok = (len > (float)HIT_EPS) & (qn > 1e-12f * len);
    *pdf = pick(m, pick(ok, len2 * len / (qn * l->area), f8s(0)), *pdf);
}

/* A diffuse bounce of lanes lam at p, n (facing the ray): the mixture's direction (coin r0's
   top bit: a light, chosen by its next 15 bits, else the cosine lobe; u1, u2 the direction's
   draws) into dir, the weight into beta; lanes whose direction is below the surface or of pdf 0
   into *dead. path_scatter's lambertian case. */
static WAI void lambertian8(struct render_ctx *ctx, const struct wide_scene *ws, i8 lam, const f8 p[3],
                            const f8 n[3], const f8 albedo[3], u8 r0, f8 u1, f8 u2, f8 dir[3], f8 beta[3],
                            i8 *dead)
{
    const i8 from_light = lam & (i8)(r0 >> 31 != 0);
    const i8 li = (i8)((((r0 >> 16) & 0x7fffu) * (uint32_t)ws->n_lights) >> 15);
    struct cone cones[WIDE_MAX_LIGHTS];
    f8 w[3] = {n[0], n[1], n[2]}, rad = wsqrt(u1), z = wsqrt(1 - u1), known = f8s(0);
    f8 ldir[3] = {f8s(0), f8s(0), f8s(0)};
    int planar = 0;
    for (int j = 0; j < ws->n_lights; j++) {
        const struct wide_light *l = &ws->lights[j];
        const i8 chose = from_light & (li == j);
        if (l->sphere) {
            struct cone *c = &cones[j];
            cone_of(l, p, c);
            if (!lane_bits(chose))
                continue;
            /* sphere_cone_dir: z uniform in [cos_max, 1], about the unit vector to the centre */
            const f8 zc = 1 - u1 * c->omc, len = wsqrt(c->d2), inv = 1.0f / len;
            const i8 far = len > 0;
            rad = pick(chose, wsqrt(pick(1 - zc * zc > 0, 1 - zc * zc, f8s(0))), rad);
            z = pick(chose, zc, z);
            w[0] = pick(chose, pick(far, c->to_c[0] * inv, f8s(0)), w[0]);
            w[1] = pick(chose, pick(far, c->to_c[1] * inv, f8s(0)), w[1]);
            w[2] = pick(chose, pick(far, c->to_c[2] * inv, f8s(1)), w[2]);
            known = pick(chose, 1 / ((float)(2 * PI) * c->omc), known);
        } else if (lane_bits(chose)) {
            rect_sample8(ctx, j, l, lane_bits(chose), p, ldir, &known);
            planar |= lane_bits(chose);
        }
    }
    f8 sp, cp, cd[3];
    sincos8(u2, &sp, &cp);
    onb8_local(w, cp * rad, sp * rad, z, cd);
    const i8 pm = lane_mask(planar);
    for (int j = 0; j < 3; j++)
        cd[j] = pick(pm, ldir[j], cd[j]);
    const f8 cosine = dot8(cd, n), cos_pdf = cosine * (float)(1 / PI);
    f8 sum = f8s(0);
    for (int j = 0; j < ws->n_lights; j++) {
        const struct wide_light *l = &ws->lights[j];
        const i8 chose = from_light & (li == j);
        sum += pick(chose, known, l->sphere ? sphere_pdf8(l, &cones[j], cd) : rect_pdf8(l, p, cd));
    }
    const f8 pdf = 0.5f * lights_mean8(sum, ws->n_lights) + 0.5f * cos_pdf;
    const i8 ok = (cosine > 0) & (pdf > 0);
    const f8 f = cos_pdf / pdf;
    for (int j = 0; j < 3; j++) {
        beta[j] = pick(lam, beta[j] * (albedo[j] * f), beta[j]);
        dir[j] = pick(lam, cd[j], dir[j]);
    }
    *dead |= lam & ~ok;
}

/* path_scatter's dielectric case for the lanes of diel: the reflected or refracted direction
   (Schlick's coin u) into dir. */
static WAI void dielectric8(i8 diel, const f8 d[3], const f8 n[3], i8 front, f8 ior, f8 u, f8 dir[3])
{
    const f8 inv = 1.0f / wsqrt(dot8(d, d));
    const f8 ud[3] = {d[0] * inv, d[1] * inv, d[2] * inv};
    const f8 ratio = pick(front, 1.0f / ior, ior);
    const f8 un = dot8(ud, n), cos_t = f8_min(-un, f8s(1)), sin_t = wsqrt(1 - cos_t * cos_t);
    f8 r0 = (1 - ratio) / (1 + ratio);
    r0 *= r0;
    const f8 x = 1 - cos_t, x2 = x * x;
    const i8 refl = (ratio * sin_t > 1) | (r0 + (1 - r0) * (x2 * x2 * x) > u);
    f8 perp[3];
    for (int j = 0; j < 3; j++)
        perp[j] = (ud[j] + n[j] * cos_t) * ratio;
    const f8 para = -wsqrt(f8_abs(1.0f - dot8(perp, perp)));
    for (int j = 0; j < 3; j++)
        dir[j] = pick(diel, pick(refl, ud[j] - n[j] * (2 * un), perp[j] + n[j] * para), dir[j]);
}

/* Lane i's path on alone by the scalar integrator (path_scatter in double, bvh_hit) to its end:
   its estimate; its segments into *rays. For a pixel's last paths: a lane alone in the vectors
   costs a whole wide step (~200 ns) per segment, the scalar loop ~50. */
static vec3 lane_finish(struct render_ctx *ctx, const struct lanes *ln, int i, int last, uint64_t inc,
                        uint64_t *rays)
{
    const double *c0 = ctx->wide->centre; /* the lanes' positions are relative to it */
    ray r = {v3(ln->o[0][i] + c0[0], ln->o[1][i] + c0[1], ln->o[2][i] + c0[2]),
             v3(ln->d[0][i], ln->d[1][i], ln->d[2][i]), 0};
    vec3 beta = v3(ln->beta[0][i], ln->beta[1][i], ln->beta[2][i]), L = v3(0, 0, 0);
    struct rng rng = {i < 4 ? ln->rng.lo[i] : ln->rng.hi[i - 4], inc};
    for (int depth = ln->depth[i]; depth <= last; depth++) {
        struct hit h;
        ++*rays;
        if (!bvh_hit(ctx->sc, &r, HIT_EPS, DBL_MAX, &h)) {
            L = v3_add(L, v3_mul(beta, ctx->sc->background));
            break;
        }
        if (!path_scatter(ctx, &r, &beta, &L, &rng, &h, depth == last, 1))
            break;
    }
    return L;
}

void render_pixel_wide(struct render_ctx *ctx, int x, int y, size_t n, const struct rng *base, int last,
                       double sum[3], size_t *kept, uint64_t *nonfinite, uint64_t *rays)
{
    const struct wide_scene *ws = ctx->wide;
    const uint64_t inc = base->inc;
    struct lanes ln;
    double acc[3] = {0, 0, 0};
    size_t acc_kept = 0;
    uint64_t acc_rays = 0, acc_nonfinite = 0;
    int live = 0;
    size_t next = 0;
    for (int j = 0; j < 3; j++)
        ln.o[j] = ln.d[j] = ln.beta[j] = f8s(1);
    ln.depth = i8s(0);
    ln.rng.lo = ln.rng.hi = (u4){0, 0, 0, 0};
    for (int i = 0; i < WIDE_LANES && next < n; i++) {
        lane_start(ctx, &ln, i, x, y, next++, base);
        live |= 1 << i;
    }
    while (live) {
        if (next >= n && __builtin_popcount((unsigned)live) <= WIDE_FINISH_LANES) {
            for (; live; live &= live - 1)
                add_estimate(lane_finish(ctx, &ln, __builtin_ctz((unsigned)live), last, inc, &acc_rays), acc,
                             &acc_kept, &acc_nonfinite);
            break;
        }
        const struct wide_best hb = wide_hit(ws, ln.o, ln.d, f8s((float)HIT_EPS));
        acc_rays += (uint64_t)__builtin_popcount((unsigned)live);
        /* the hit point, the material, the normal against the ray */
        const i8 k = picki(hb.k < 0, i8s(ws->n), hb.k);
        f8 p[3], no[3], nf[3], albedo[3], emit[3];
        for (int j = 0; j < 3; j++) {
            p[j] = ln.o[j] + ln.d[j] * hb.t;
            albedo[j] = wide_col(ws, WC_ALBEDO + j, k);
            emit[j] = wide_col(ws, WC_EMIT + j, k);
        }
        const f8 type = wide_col(ws, WC_TYPE, k);
        wide_normal(ws, ln.o, ln.d, p, hb, k, no);
        const i8 front = dot8(ln.d, no) < 0, flip = ~front & (i8)f8s(-0.0f);
        for (int j = 0; j < 3; j++)
            nf[j] = (f8)((i8)no[j] ^ flip);
        const i8 live_m = lane_mask(live), miss = hb.k < 0, is_emit = type == WM_EMIT;
        i8 end = live_m & (is_emit | (ln.depth == last));
        const i8 gain = is_emit & (front | miss);
        f8 c[3];
        for (int j = 0; j < 3; j++)
            c[j] = pick(gain, ln.beta[j] * emit[j], f8s(0));
        /* every lane draws the same three numbers per segment: a sample's stream depends on
           its own path only */
        const u8 r0 = rng8_u32(&ln.rng, inc);
        const f8 u1 = u32_unit(rng8_u32(&ln.rng, inc)), u2 = u32_unit(rng8_u32(&ln.rng, inc));
        const i8 lam = live_m & ~end & (type == WM_LAMBERTIAN),
                 diel = live_m & ~end & (type == WM_DIELECTRIC);
        f8 nd[3] = {ln.d[0], ln.d[1], ln.d[2]};
        if (lane_bits(lam))
            lambertian8(ctx, ws, lam, p, nf, albedo, r0, u1, u2, nd, ln.beta, &end);
        if (lane_bits(diel))
            dielectric8(diel, ln.d, nf, front, wide_col(ws, WC_IOR, k), u1, nd);
        /* the new origin off the surface on the new direction's side, beyond the float
           rounding of p = o + t d (which t_min alone leaves to grazing directions: acne): 16
           float ulps of |p| + |o|, the lane's own scale (one offset for the scene, of its whole
           reach, was the diameter of a glass sphere of radius 0.05 on a floor 2e5 across) */
        f8 p_most = f8_abs(p[0]), o_most = f8_abs(ln.o[0]);
        for (int j = 1; j < 3; j++)
            p_most = f8_max(p_most, f8_abs(p[j])), o_most = f8_max(o_most, f8_abs(ln.o[j]));
        const f8 off = (f8)((i8)((p_most + o_most) * 0x1p-20f) | ((i8)dot8(nd, nf) & (i8)f8s(-0.0f)));
        for (int j = 0; j < 3; j++)
            ln.o[j] = p[j] + nf[j] * off, ln.d[j] = nd[j];
        ln.depth += 1;
        for (int b = lane_bits(end) & live; b; b &= b - 1) {
            const int i = __builtin_ctz((unsigned)b);
            add_estimate(v3(c[0][i], c[1][i], c[2][i]), acc, &acc_kept, &acc_nonfinite);
            if (next < n)
                lane_start(ctx, &ln, i, x, y, next++, base);
            else
                live &= ~(1 << i);
        }
    }
    for (int j = 0; j < 3; j++)
        sum[j] += acc[j];
    *kept += acc_kept;
    *nonfinite += acc_nonfinite;
    *rays += acc_rays;
}
#else
#include <stdlib.h>

/* Without the kernel wide_usable is 0 and ctx->wide NULL: never called, reaching it is a bug. */
void render_pixel_wide(struct render_ctx *ctx, int x, int y, size_t n, const struct rng *base, int last,
                       double sum[3], size_t *kept, uint64_t *nonfinite, uint64_t *rays)
{
    abort();
}
#endif
