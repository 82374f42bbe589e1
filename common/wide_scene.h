/* wide_scene: the tables of the wide path tracer (render_wide.c) and its nearest-hit test of four
   rays against every prim of a one-node scene in double lanes, branch-free, with the winner's
   outward normal kept as it goes. Internal to common/. */
#ifndef WIDE_SCENE_H
#define WIDE_SCENE_H

#include <float.h>

#include "render_wide.h"
#include "wide_math.h"

enum { WK_RECT_X, WK_RECT_Y, WK_RECT_Z, WK_SPHERE, WK_BOX };

/* A prim's constants, each in all eight lanes: a rect's k, a0, a1, b0, b1; a sphere's centre,
   radius^2 and 1 / radius; a box's cos_y, sin_y, offset, lo and hi. */
struct wide_prim {
    f8 v[12];
    int kind, prim;
} __attribute__((aligned(32)));

/* The columns of the prims' materials and normals, one entry per prim and the miss (entry n):
   albedo, ior, emission (a light's, or the background for the miss), type, a rect's outward
   normal (0 for the others), and 1 for a sphere or box, whose normal is made from the hit. */
enum { WM_LAMBERTIAN, WM_DIELECTRIC, WM_EMIT };
enum { WC_ALBEDO = 0, WC_IOR = 3, WC_EMIT = 4, WC_TYPE = 7, WC_N = 8, WC_CURVED = 11, WC_COLUMNS = 12 };

/* A light: a rect (axis-aligned, unit axes) or a sphere. */
struct wide_light {
    int sphere, on, oa, ob;
    float k, a0, a1, b0, b1, area;
    float c[3], r2;
};

struct wide_scene {
    const struct scene *sc;
    int n, n_lights;
    int end[WK_BOX + 1]; /* prims are grouped by kind: kind j's end at end[j] */
    /* a ball holding every prim: camera rays start near it, and the lanes' positions (the tables'
       and the rays') are relative to its centre, so they round at the scene's size, not at its
       distance from the origin (cornell-book3 moved by 1e6 rounded to 1/16 in float) */
    double centre[3], radius;
    struct wide_prim *prims;
    f8 col[WC_COLUMNS][2]; /* entries 0-7, 8-15 */
    struct wide_light *lights;
};

/* The lanes' nearest hits: t and the prim's place in the order (-1: none). */
struct wide_best {
    f8 t;
    i8 k;
};

static WAI void wide_keep(struct wide_best *b, i8 m, f8 t, int32_t k)
{
    b->t = pick(m, t, b->t);
    b->k = picki(m, i8s(k), b->k);
}

/* hit_rect's test for a rect of normal axis on and in-plane axes oa, ob (constants). */
static WAI void wide_rect(const f8 o[3], const f8 d[3], f8 t_min, struct wide_best *b,
                          const struct wide_prim *e, int32_t k, int on, int oa, int ob)
{
    const f8 t = (e->v[0] - o[on]) / d[on];
    i8 m = (t > t_min) & (t < b->t);
    const f8 pa = o[oa] + d[oa] * t, pb = o[ob] + d[ob] * t;
    m &= ~((pa < e->v[1]) | (pa > e->v[2]) | (pb < e->v[3]) | (pb > e->v[4]));
    wide_keep(b, m, t, k);
}

static WAI void wide_sphere(const f8 o[3], const f8 d[3], f8 t_min, struct wide_best *b,
                            const struct wide_prim *e, int32_t k)
{
    const f8 ocx = o[0] - e->v[0], ocy = o[1] - e->v[1], ocz = o[2] - e->v[2];
    const f8 a = dot8(d, d);
    const f8 half_b = ocx * d[0] + ocy * d[1] + ocz * d[2];
    /* half_b^2 - a c as a (r^2 - |f|^2), f the centre's offset across the ray (Haines et al.,
       Ray Tracing Gems ch. 7): in float, b^2 - a c of terms ~|o - c|^2 put a grazing ray's hit
       up to 1e-2 off a small far sphere, beyond the new origin's offset (acne: dark rims) */
    const f8 s = half_b / a, fx = ocx - s * d[0], fy = ocy - s * d[1], fz = ocz - s * d[2];
    const f8 disc = a * (e->v[3] - (fx * fx + fy * fy + fz * fz));
    const i8 ok = ~((disc < 0) | (a == 0));
    const f8 sq = wsqrt(disc);
    const f8 lo = t_min * a, hi = b->t * a;
    const f8 at0 = -half_b - sq, at1 = -half_b + sq;
    const i8 m0 = (at0 > lo) & (at0 < hi), m1 = (at1 > lo) & (at1 < hi);
    wide_keep(b, ok & (m0 | m1), pick(m0, at0, at1) / a, k);
}

/* one slab of the box: the nearest entry and farthest exit so far, and (axes) their axes */
static WAI void wide_slab(f8 lo, f8 hi, f8 o, f8 d, int axis, f8 *t_near, f8 *t_far, i8 *a_near, i8 *a_far)
{
    const i8 neg = (i8)d < 0;
    const f8 near = pick(neg, hi, lo), far = pick(neg, lo, hi);
    const f8 inv = 1.0f / d;
    const f8 tn = (near - o) * inv, tf = (far - o) * inv;
    const i8 mn = tn > *t_near, mf = tf < *t_far;
    *t_near = pick(mn, tn, *t_near);
    *t_far = pick(mf, tf, *t_far);
    if (a_near) {
        *a_near = picki(mn, i8s(axis), *a_near);
        *a_far = picki(mf, i8s(axis), *a_far);
    }
}

/* The ray in the box's frame (its rotate_y + translate undone). */
static WAI void box_frame(const f8 o[3], const f8 d[3], const struct wide_prim *e, f8 lo[3], f8 ld[3])
{
    const f8 c = e->v[0], s = e->v[1];
    const f8 wx = o[0] - e->v[2], wy = o[1] - e->v[3], wz = o[2] - e->v[4];
    lo[0] = c * wx - s * wz, lo[1] = wy, lo[2] = s * wx + c * wz;
    ld[0] = c * d[0] - s * d[2], ld[1] = d[1], ld[2] = s * d[0] + c * d[2];
}

/* hit_box's test; with axes, also the axes of its entry and exit. */
static WAI void box_slabs(const f8 o[3], const f8 d[3], const struct wide_prim *e, f8 *t_near, f8 *t_far,
                          i8 *a_near, i8 *a_far)
{
    f8 lo[3], ld[3];
    box_frame(o, d, e, lo, ld);
    *t_near = f8s(-INFINITY), *t_far = f8s(INFINITY);
    wide_slab(e->v[5], e->v[8], lo[0], ld[0], 0, t_near, t_far, a_near, a_far);
    wide_slab(e->v[6], e->v[9], lo[1], ld[1], 1, t_near, t_far, a_near, a_far);
    wide_slab(e->v[7], e->v[10], lo[2], ld[2], 2, t_near, t_far, a_near, a_far);
}

static WAI void wide_box(const f8 o[3], const f8 d[3], f8 t_min, struct wide_best *b,
                         const struct wide_prim *e, int32_t k)
{
    f8 t_near, t_far;
    box_slabs(o, d, e, &t_near, &t_far, NULL, NULL);
    const i8 entry = (t_near > t_min) & (t_near < b->t);
    const i8 leave = (t_far > t_min) & (t_far < b->t);
    wide_keep(b, ~(t_near > t_far) & (entry | leave), pick(entry, t_near, t_far), k);
}

/* The box's outward normal for lanes hitting it at t (its test again, with the axes). */
static WAI void box_normal(const f8 o[3], const f8 d[3], f8 t, const struct wide_prim *e, f8 n[3])
{
    f8 t_near, t_far, lo[3], ld[3];
    i8 a_near = i8s(0), a_far = i8s(0);
    box_slabs(o, d, e, &t_near, &t_far, &a_near, &a_far);
    box_frame(o, d, e, lo, ld);
    const i8 entry = t == t_near;
    const i8 axis = picki(entry, a_near, a_far);
    const i8 ax0 = axis == 0, ax1 = axis == 1, ax2 = axis == 2;
    /* the face's normal against d along its axis (hit_box's), outward: reversed on an exit */
    const f8 da = pick(ax0, ld[0], pick(ax1, ld[1], ld[2]));
    const f8 nv = (f8)((i8)pick(da > 0, f8s(-1), f8s(1)) ^ ((i8)f8s(-0.0f) & ~entry));
    const f8 lx = (f8)((i8)nv & ax0), ly = (f8)((i8)nv & ax1), lz = (f8)((i8)nv & ax2);
    const f8 c = e->v[0], s = e->v[1];
    n[0] = c * lx + s * lz, n[1] = ly, n[2] = c * lz - s * lx;
}

/* Every prim against the lanes' rays o + t d, t in (t_min, FLT_MAX), kind by kind (a tie
   between two prims at the same t, on an edge where they meet: the first in this order). */
static WAI struct wide_best wide_hit(const struct wide_scene *ws, const f8 o[3], const f8 d[3], f8 t_min)
{
    struct wide_best b = {f8s(FLT_MAX), i8s(-1)};
    const struct wide_prim *e = ws->prims;
    int k = 0;
    for (; k < ws->end[WK_RECT_X]; k++)
        wide_rect(o, d, t_min, &b, &e[k], k, 0, 1, 2);
    for (; k < ws->end[WK_RECT_Y]; k++)
        wide_rect(o, d, t_min, &b, &e[k], k, 1, 0, 2);
    for (; k < ws->end[WK_RECT_Z]; k++)
        wide_rect(o, d, t_min, &b, &e[k], k, 2, 0, 1);
    for (; k < ws->end[WK_SPHERE]; k++)
        wide_sphere(o, d, t_min, &b, &e[k], k);
    for (; k < ws->end[WK_BOX]; k++)
        wide_box(o, d, t_min, &b, &e[k], k);
    return b;
}

/* Column c of the prims' table at the lanes' entries k (the miss: entry n). */
static WAI f8 wide_col(const struct wide_scene *ws, int c, i8 k)
{
    return lookup16(ws->col[c][0], ws->col[c][1], k);
}

/* The outward normals of the hits b at entries k (p = o + t d): a rect's from the table, a
   sphere's or box's made for the prims some lane hit. */
static WAI void wide_normal(const struct wide_scene *ws, const f8 o[3], const f8 d[3], const f8 p[3],
                            struct wide_best b, i8 k, f8 n[3])
{
    for (int j = 0; j < 3; j++)
        n[j] = wide_col(ws, WC_N + j, k);
    for (int bits = lane_bits(wide_col(ws, WC_CURVED, k) != 0); bits;) {
        const int kk = b.k[__builtin_ctz((unsigned)bits)];
        const struct wide_prim *e = &ws->prims[kk];
        const i8 m = b.k == kk;
        bits &= ~lane_bits(m);
        f8 c[3];
        if (e->kind == WK_SPHERE) {
            for (int j = 0; j < 3; j++)
                c[j] = (p[j] - e->v[j]) * e->v[4];
        } else {
            box_normal(o, d, b.t, e, c);
        }
        for (int j = 0; j < 3; j++)
            n[j] = pick(m, c[j], n[j]);
    }
}

#endif
