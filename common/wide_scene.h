/* wide_scene: the tables of the wide path tracer (render_wide.c) and its nearest-hit test of four
   rays against every prim of a one-node scene in double lanes, branch-free, with the winner's
   outward normal kept as it goes. Internal to common/. */
#ifndef WIDE_SCENE_H
#define WIDE_SCENE_H

#include <float.h>

#include "render_wide.h"
#include "wide_math.h"

enum { WK_RECT_X, WK_RECT_Y, WK_RECT_Z, WK_SPHERE, WK_BOX };

/* A prim's constants, each in all four lanes: a rect's k, a0, a1, b0, b1; a sphere's centre,
   radius^2 and 1 / radius; a box's cos_y, sin_y, offset, lo and hi. */
struct wide_prim {
    d4 v[12];
    int kind, prim;
} __attribute__((aligned(32)));

/* A prim's material and normal as 32-byte rows (gathered per lane and transposed): albedo and
   ior; emission (a light's, or the background for the miss entry) and the type; a rect's outward
   normal (0 for the others) and 1 for a sphere or box, whose normal is made from the hit. */
enum { WM_LAMBERTIAN, WM_DIELECTRIC, WM_EMIT };
struct wide_mat {
    double albedo[3], ior, emit[3], type, n[3], curved;
} __attribute__((aligned(32)));

/* A light: a rect (axis-aligned, unit axes) or a sphere. */
struct wide_light {
    int sphere, on, oa, ob;
    double k, a0, a1, b0, b1, area, ball_c[3], ball_r2, ball_r2_out;
    double c[3], r2;
};

struct wide_scene {
    const struct scene *sc;
    int n, n_lights;
    int end[WK_BOX + 1]; /* prims are grouped by kind: kind j's end at end[j] */
    struct wide_prim *prims;
    struct wide_mat *mats; /* n + 1: entry n is the miss (the background) */
    struct wide_light *lights;
};

/* The lanes' nearest hits: t and the prim's place in the order (-1: none). */
struct wide_best {
    d4 t;
    i4 k;
};

static WAI void wide_keep(struct wide_best *b, i4 m, d4 t, int64_t k)
{
    b->t = pick(m, t, b->t);
    b->k = (i4)pick(m, (d4)(i4){k, k, k, k}, (d4)b->k);
}

/* hit_rect's test for a rect of normal axis on and in-plane axes oa, ob (constants). */
static WAI void wide_rect(const d4 o[3], const d4 d[3], d4 t_min, struct wide_best *b, const struct wide_prim *e,
                          int64_t k, int on, int oa, int ob)
{
    const d4 t = (e->v[0] - o[on]) / d[on];
    i4 m = (t > t_min) & (t < b->t);
    const d4 pa = o[oa] + d[oa] * t, pb = o[ob] + d[ob] * t;
    m &= ~((pa < e->v[1]) | (pa > e->v[2]) | (pb < e->v[3]) | (pb > e->v[4]));
    wide_keep(b, m, t, k);
}

static WAI void wide_sphere(const d4 o[3], const d4 d[3], d4 t_min, struct wide_best *b,
                            const struct wide_prim *e, int64_t k)
{
    const d4 ocx = o[0] - e->v[0], ocy = o[1] - e->v[1], ocz = o[2] - e->v[2];
    const d4 a = dot4(d, d);
    const d4 half_b = ocx * d[0] + ocy * d[1] + ocz * d[2];
    const d4 cc = (ocx * ocx + ocy * ocy + ocz * ocz) - e->v[3];
    const d4 disc = half_b * half_b - a * cc;
    const i4 ok = ~((disc < 0) | (a == 0));
    const d4 sq = wsqrt(disc);
    const d4 lo = t_min * a, hi = b->t * a;
    const d4 at0 = -half_b - sq, at1 = -half_b + sq;
    const i4 m0 = (at0 > lo) & (at0 < hi), m1 = (at1 > lo) & (at1 < hi);
    wide_keep(b, ok & (m0 | m1), pick(m0, at0, at1) / a, k);
}

/* one slab of the box: the nearest entry and farthest exit so far, and (axes) their axes */
static WAI void wide_slab(d4 lo, d4 hi, d4 o, d4 d, int axis, d4 *t_near, d4 *t_far, i4 *a_near, i4 *a_far)
{
    const i4 neg = (i4)d < 0;
    const d4 near = pick(neg, hi, lo), far = pick(neg, lo, hi);
    const d4 inv = 1.0 / d;
    const d4 tn = (near - o) * inv, tf = (far - o) * inv;
    const i4 mn = tn > *t_near, mf = tf < *t_far;
    *t_near = pick(mn, tn, *t_near);
    *t_far = pick(mf, tf, *t_far);
    if (a_near) {
        const d4 a = (d4)(i4){axis, axis, axis, axis};
        *a_near = (i4)pick(mn, a, (d4)*a_near);
        *a_far = (i4)pick(mf, a, (d4)*a_far);
    }
}

/* The ray in the box's frame (its rotate_y + translate undone). */
static WAI void box_frame(const d4 o[3], const d4 d[3], const struct wide_prim *e, d4 lo[3], d4 ld[3])
{
    const d4 c = e->v[0], s = e->v[1];
    const d4 wx = o[0] - e->v[2], wy = o[1] - e->v[3], wz = o[2] - e->v[4];
    lo[0] = c * wx - s * wz, lo[1] = wy, lo[2] = s * wx + c * wz;
    ld[0] = c * d[0] - s * d[2], ld[1] = d[1], ld[2] = s * d[0] + c * d[2];
}

/* hit_box's test; with axes, also the axes of its entry and exit. */
static WAI void box_slabs(const d4 o[3], const d4 d[3], const struct wide_prim *e, d4 *t_near, d4 *t_far,
                          i4 *a_near, i4 *a_far)
{
    d4 lo[3], ld[3];
    box_frame(o, d, e, lo, ld);
    *t_near = d4s(-INFINITY), *t_far = d4s(INFINITY);
    wide_slab(e->v[5], e->v[8], lo[0], ld[0], 0, t_near, t_far, a_near, a_far);
    wide_slab(e->v[6], e->v[9], lo[1], ld[1], 1, t_near, t_far, a_near, a_far);
    wide_slab(e->v[7], e->v[10], lo[2], ld[2], 2, t_near, t_far, a_near, a_far);
}

static WAI void wide_box(const d4 o[3], const d4 d[3], d4 t_min, struct wide_best *b, const struct wide_prim *e,
                         int64_t k)
{
    d4 t_near, t_far;
    box_slabs(o, d, e, &t_near, &t_far, NULL, NULL);
    const i4 entry = (t_near > t_min) & (t_near < b->t);
    const i4 leave = (t_far > t_min) & (t_far < b->t);
    wide_keep(b, ~(t_near > t_far) & (entry | leave), pick(entry, t_near, t_far), k);
}

/* The box's outward normal for lanes hitting it at t (its test again, with the axes). */
static WAI void box_normal(const d4 o[3], const d4 d[3], d4 t, const struct wide_prim *e, d4 n[3])
{
    d4 t_near, t_far, lo[3], ld[3];
    i4 a_near = {0, 0, 0, 0}, a_far = {0, 0, 0, 0};
    box_slabs(o, d, e, &t_near, &t_far, &a_near, &a_far);
    box_frame(o, d, e, lo, ld);
    const i4 entry = t == t_near;
    const i4 axis = (i4)pick(entry, (d4)a_near, (d4)a_far);
    const i4 ax0 = axis == 0, ax1 = axis == 1, ax2 = axis == 2;
    /* the face's normal against d along its axis (hit_box's), outward: reversed on an exit */
    const d4 da = pick(ax0, ld[0], pick(ax1, ld[1], ld[2]));
    const d4 nv = (d4)((i4)pick(da > 0, d4s(-1), d4s(1)) ^ ((i4)d4s(-0.0) & ~entry));
    const d4 lx = (d4)((i4)nv & ax0), ly = (d4)((i4)nv & ax1), lz = (d4)((i4)nv & ax2);
    const d4 c = e->v[0], s = e->v[1];
    n[0] = c * lx + s * lz, n[1] = ly, n[2] = c * lz - s * lx;
}

/* Every prim against the lanes' rays o + t d, t in (t_min, DBL_MAX), kind by kind (a tie
   between two prims at the same t, on an edge where they meet: the first in this order). */
static WAI struct wide_best wide_hit(const struct wide_scene *ws, const d4 o[3], const d4 d[3], d4 t_min)
{
    struct wide_best b = {d4s(DBL_MAX), (i4){-1, -1, -1, -1}};
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

/* The outward normals of the hits b (p = o + t d): rows[2] (a rect's, from its material row)
   where it is not curved, else the sphere's or box's own, made for the prims some lane hit. */
static WAI void wide_normal(const struct wide_scene *ws, const d4 o[3], const d4 d[3], const d4 p[3],
                            struct wide_best b, const d4 row[4], d4 n[3])
{
    n[0] = row[0], n[1] = row[1], n[2] = row[2];
    for (int bits = lane_bits(row[3] != 0); bits;) {
        const int k = (int)b.k[__builtin_ctz((unsigned)bits)];
        const struct wide_prim *e = &ws->prims[k];
        const i4 m = b.k == k;
        bits &= ~lane_bits(m);
        d4 c[3];
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
