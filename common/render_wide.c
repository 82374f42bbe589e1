/* render_wide: a pixel's camera paths four at a time, their state by component in double lanes
   from the camera to the estimate (render_wide.h): the hit (wide_scene.h), the light or the
   background met, a diffuse bounce with the light mixture, a dielectric's reflection or
   refraction, all lanes at once under masks. Only the rect lights' points are taken lane by lane
   (in lane order from the pixel's shared sets), and a lane's start and its estimate's sum. */
#include "render_wide.h"

#include <float.h>

#include "render_path.h"
#include "wide_scene.h"

/* The paths in flight: ray, weight, segments traced, rng state, by component. */
struct lanes {
    d4 o[3], d[3], beta[3];
    i4 depth;
    u4 rng;
};

/* Camera sample s of pixel (x, y) into lane i, its rng as path_start's (render_lanes.c). */
static WAI void lane_start(struct render_ctx *ctx, struct lanes *ln, int i, int x, int y, size_t s,
                           const struct rng *base)
{
    const int w = ctx->rs.width, hgt = ctx->rs.height;
    struct rng r = {rng_mix64(base->state + s), base->inc};
    const struct pt2 p = ctx->pixel_pts[s];
    const ray cr = camera_ray(ctx->cam, (x + p.x) / w, (hgt - y - p.y) / hgt, &r);
    ln->o[0][i] = cr.orig.x, ln->o[1][i] = cr.orig.y, ln->o[2][i] = cr.orig.z;
    ln->d[0][i] = cr.dir.x, ln->d[1][i] = cr.dir.y, ln->d[2][i] = cr.dir.z;
    ln->beta[0][i] = ln->beta[1][i] = ln->beta[2][i] = 1;
    ln->depth[i] = 0;
    ln->rng[i] = r.state;
}

/* A sphere light's cone from the lanes' points p: centre minus p, its length^2, 1 - cos of the
   half-angle (2 inside: sphere_one_minus_cos). */
struct cone {
    d4 to_c[3], d2, omc;
    i4 inside;
};

static WAI void cone_of(const struct wide_light *l, const d4 p[3], struct cone *c)
{
    for (int j = 0; j < 3; j++)
        c->to_c[j] = l->c[j] - p[j];
    c->d2 = dot4(c->to_c, c->to_c);
    c->inside = c->d2 <= l->r2;
    const d4 s2 = l->r2 / c->d2;
    c->omc = pick(c->inside, d4s(2), s2 / (1 + wsqrt(1 - s2)));
}

static WAI d4 lights_mean4(d4 sum, int n)
{
    return n == 1 ? sum : n == 2 ? sum * 0.5 : sum / n;
}

/* sphere_pdf for directions dir */
static WAI d4 sphere_pdf4(const struct wide_light *l, const struct cone *c, const d4 dir[3])
{
    const d4 dc = dot4(dir, c->to_c);
    const i4 in = dc * d4_abs(dc) >= (c->d2 - l->r2) * dot4(dir, dir);
    const d4 pdf = pick(in, 1 / (2 * PI * c->omc), d4s(0));
    return pick(c->inside, d4s(1 / (4 * PI)), pdf);
}

/* rect_pdf_hit (its cone test is a shortcut only: it never rejects what this accepts) */
static WAI d4 rect_pdf4(const struct wide_light *l, const d4 p[3], const d4 dir[3])
{
    const d4 dn = dir[l->on], t = (l->k - p[l->on]) / dn;
    const d4 qa = p[l->oa] + dir[l->oa] * t, qb = p[l->ob] + dir[l->ob] * t;
    const d4 dd = dot4(dir, dir), sd = wsqrt(dd), adn = d4_abs(dn);
    i4 ok = (t > HIT_EPS) & (t < DBL_MAX) & (adn > 1e-12 * sd);
    ok &= ~((qa < l->a0) | (qa > l->a1) | (qb < l->b0) | (qb > l->b1));
    return pick(ok, t * t * dd * sd / (adn * l->area), d4s(0));
}

/* The rect light l's point for each lane of `chose` (the pixel's set, lanes in order), the
   direction to it from p and its pdf (planar_sample), into dir and pdf on those lanes. */
static WAI void rect_sample4(struct render_ctx *ctx, int li, const struct wide_light *l, int chose,
                             const d4 p[3], d4 dir[3], d4 *pdf)
{
    d4 sx = d4s(0), sy = d4s(0);
    for (int b = chose; b; b &= b - 1) {
        const int i = __builtin_ctz((unsigned)b);
        struct pt2 turn;
        int turned = 0;
        const struct pt2 s = next_light_point(ctx, li, &turn, &turned);
        sx[i] = s.x, sy[i] = s.y;
    }
    d4 to_q[3];
    to_q[l->on] = l->k - p[l->on];
    to_q[l->oa] = (l->a0 + sx * (l->a1 - l->a0)) - p[l->oa];
    to_q[l->ob] = (l->b0 + sy * (l->b1 - l->b0)) - p[l->ob];
    const d4 len2 = dot4(to_q, to_q), len = wsqrt(len2), inv = 1.0 / len, qn = d4_abs(to_q[l->on]);
    const i4 m = lane_mask(chose);
    for (int j = 0; j < 3; j++)
        dir[j] = pick(m, to_q[j] * inv, dir[j]);
    const i4 ok = (len > HIT_EPS) & (qn > 1e-12 * len);
    *pdf = pick(m, pick(ok, len2 * len / (qn * l->area), d4s(0)), *pdf);
}

/* A diffuse bounce of lanes lam at p, n (facing the ray): the mixture's direction (coin r0's
   top bit: a light, chosen by its other bits, else the cosine lobe; u1, u2 the direction's
   draws) into dir, the weight into beta; lanes whose direction is below the surface or of pdf 0
   into *dead. path_scatter's lambertian case. */
static WAI void lambertian4(struct render_ctx *ctx, const struct wide_scene *ws, i4 lam, const d4 p[3],
                            const d4 n[3], const d4 albedo[3], u4 r0, d4 u1, d4 u2, d4 dir[3], d4 beta[3],
                            i4 *dead)
{
    const i4 from_light = lam & (i4)(r0 >> 31 != 0);
    const u4 li = ((r0 & 0x7fffffffu) * (uint64_t)ws->n_lights) >> 31;
    struct cone cones[WIDE_MAX_LIGHTS];
    d4 w[3] = {n[0], n[1], n[2]}, rad = wsqrt(u1), z = wsqrt(1 - u1), known = d4s(0);
    d4 ldir[3] = {d4s(0), d4s(0), d4s(0)};
    int planar = 0;
    for (int j = 0; j < ws->n_lights; j++) {
        const struct wide_light *l = &ws->lights[j];
        const i4 chose = from_light & (i4)(li == (uint64_t)j);
        if (l->sphere) {
            struct cone *c = &cones[j];
            cone_of(l, p, c);
            if (!lane_bits(chose))
                continue;
            /* sphere_cone_dir: z uniform in [cos_max, 1], about the unit vector to the centre */
            const d4 zc = 1 - u1 * c->omc, len = wsqrt(c->d2), inv = 1.0 / len;
            const i4 far = len > 0;
            rad = pick(chose, wsqrt(pick(1 - zc * zc > 0, 1 - zc * zc, d4s(0))), rad);
            z = pick(chose, zc, z);
            w[0] = pick(chose, pick(far, c->to_c[0] * inv, d4s(0)), w[0]);
            w[1] = pick(chose, pick(far, c->to_c[1] * inv, d4s(0)), w[1]);
            w[2] = pick(chose, pick(far, c->to_c[2] * inv, d4s(1)), w[2]);
            known = pick(chose, 1 / (2 * PI * c->omc), known);
        } else if (lane_bits(chose)) {
            rect_sample4(ctx, j, l, lane_bits(chose), p, ldir, &known);
            planar |= lane_bits(chose);
        }
    }
    d4 sp, cp, cd[3];
    sincos4(u2, &sp, &cp);
    onb4_local(w, cp * rad, sp * rad, z, cd);
    const i4 pm = lane_mask(planar);
    for (int j = 0; j < 3; j++)
        cd[j] = pick(pm, ldir[j], cd[j]);
    const d4 cosine = dot4(cd, n), cos_pdf = cosine / PI;
    d4 sum = d4s(0);
    for (int j = 0; j < ws->n_lights; j++) {
        const struct wide_light *l = &ws->lights[j];
        const i4 chose = from_light & (i4)(li == (uint64_t)j);
        sum += pick(chose, known, l->sphere ? sphere_pdf4(l, &cones[j], cd) : rect_pdf4(l, p, cd));
    }
    const d4 pdf = 0.5 * lights_mean4(sum, ws->n_lights) + 0.5 * cos_pdf;
    const i4 ok = (cosine > 0) & (pdf > 0);
    const d4 f = cos_pdf / pdf;
    for (int j = 0; j < 3; j++) {
        beta[j] = pick(lam, beta[j] * (albedo[j] * f), beta[j]);
        dir[j] = pick(lam, cd[j], dir[j]);
    }
    *dead |= lam & ~ok;
}

/* path_scatter's dielectric case for the lanes of diel: the reflected or refracted direction
   (Schlick's coin u) into dir. */
static WAI void dielectric4(i4 diel, const d4 d[3], const d4 n[3], i4 front, d4 ior, d4 u, d4 dir[3])
{
    const d4 inv = 1.0 / wsqrt(dot4(d, d));
    const d4 ud[3] = {d[0] * inv, d[1] * inv, d[2] * inv};
    const d4 ratio = pick(front, 1.0 / ior, ior);
    const d4 un = dot4(ud, n), cos_t = d4_min(-un, d4s(1)), sin_t = wsqrt(1 - cos_t * cos_t);
    d4 r0 = (1 - ratio) / (1 + ratio);
    r0 *= r0;
    const d4 x = 1 - cos_t, x2 = x * x;
    const i4 refl = (ratio * sin_t > 1) | (r0 + (1 - r0) * (x2 * x2 * x) > u);
    d4 perp[3];
    for (int j = 0; j < 3; j++)
        perp[j] = (ud[j] + n[j] * cos_t) * ratio;
    const d4 para = -wsqrt(d4_abs(1.0 - dot4(perp, perp)));
    for (int j = 0; j < 3; j++)
        dir[j] = pick(diel, pick(refl, ud[j] - n[j] * (2 * un), perp[j] + n[j] * para), dir[j]);
}

void render_pixel_wide(struct render_ctx *ctx, int x, int y, size_t n, const struct rng *base,
                                   int last, double sum[3], size_t *kept, uint64_t *nonfinite, uint64_t *rays)
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
        ln.o[j] = ln.d[j] = ln.beta[j] = d4s(1);
    ln.depth = (i4){0, 0, 0, 0};
    ln.rng = (u4){0, 0, 0, 0};
    for (int i = 0; i < WIDE_LANES && next < n; i++) {
        lane_start(ctx, &ln, i, x, y, next++, base);
        live |= 1 << i;
    }
    while (live) {
        const struct wide_best hb = wide_hit(ws, ln.o, ln.d, d4s(HIT_EPS));
        acc_rays += (uint64_t)__builtin_popcount((unsigned)live);
        /* the hit point, the material, the normal against the ray */
        d4 p[3], no[3], nf[3], m0[4], m1[4], m2[4];
        for (int j = 0; j < 3; j++)
            p[j] = ln.o[j] + ln.d[j] * hb.t;
        const void *rows[WIDE_LANES];
        for (int i = 0; i < WIDE_LANES; i++)
            rows[i] = &ws->mats[hb.k[i] < 0 ? ws->n : hb.k[i]];
        transpose4(rows, offsetof(struct wide_mat, albedo), m0);
        transpose4(rows, offsetof(struct wide_mat, emit), m1);
        transpose4(rows, offsetof(struct wide_mat, n), m2);
        wide_normal(ws, ln.o, ln.d, p, hb, m2, no);
        const i4 front = dot4(ln.d, no) < 0, flip = ~front & (i4)d4s(-0.0);
        for (int j = 0; j < 3; j++)
            nf[j] = (d4)((i4)no[j] ^ flip);
        const i4 live_m = lane_mask(live), miss = hb.k < 0, emit = m1[3] == WM_EMIT;
        i4 end = live_m & (emit | (ln.depth == last));
        const i4 gain = emit & (front | miss);
        d4 c[3];
        for (int j = 0; j < 3; j++)
            c[j] = pick(gain, ln.beta[j] * m1[j], d4s(0));
        /* every lane draws the same three numbers per segment: a sample's stream depends on
           its own path only */
        const u4 r0 = rng4_u32(&ln.rng, inc);
        const d4 u1 = u32_unit(rng4_u32(&ln.rng, inc)), u2 = u32_unit(rng4_u32(&ln.rng, inc));
        const i4 lam = live_m & ~end & (m1[3] == WM_LAMBERTIAN), diel = live_m & ~end & (m1[3] == WM_DIELECTRIC);
        d4 nd[3] = {ln.d[0], ln.d[1], ln.d[2]};
        if (lane_bits(lam))
            lambertian4(ctx, ws, lam, p, nf, m0, r0, u1, u2, nd, ln.beta, &end);
        if (lane_bits(diel))
            dielectric4(diel, ln.d, nf, front, m0[3], u1, nd);
        for (int j = 0; j < 3; j++)
            ln.o[j] = p[j], ln.d[j] = nd[j];
        ln.depth -= -1;
        for (int b = lane_bits(end) & live; b; b &= b - 1) {
            const int i = __builtin_ctz((unsigned)b);
            add_estimate(v3(c[0][i], c[1][i], c[2][i]), acc, &acc_kept, &acc_nonfinite);
            if (next < n)
                lane_start(ctx, &ln, i, x, y, next++, base);
            else
                live &= ~(1 << i);
        }
    }
    for (int k = 0; k < 3; k++)
        sum[k] += acc[k];
    *kept += acc_kept;
    *nonfinite += acc_nonfinite;
    *rays += acc_rays;
}
