/* shape: ray intersection for every primitive type, dispatched by one switch (no function
   pointers per ray). A rotate_y + translate is folded into the geometry at load where the shape
   allows (shape_bake.c); for the rest the ray is moved into object space first. */
#include "shape.h"

#include <stddef.h>
#include <string.h>

#include "shape_inline.h"

/* Both roots t0 <= t1 of |o + t d - c| = rad; 0 when the line misses the sphere. */
static int sphere_roots(vec3 c, double rad, const ray *r, double *t0, double *t1)
{
    double a, half_b, sq;
    if (!sphere_quadratic(c, rad, r, &a, &half_b, &sq))
        return 0;
    double inv_a = 1 / a;
    *t0 = (-half_b - sq) * inv_a;
    *t1 = (-half_b + sq) * inv_a;
    return 1;
}

static int hit_disk(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h)
{
    double t, dn;
    if (!disk_plane(p, r->orig, r->dir, t_min, t_max, &t, &dn))
        return 0;
    h->t = t;
    h->p = ray_at(r, t);
    set_face(h, r, p->g.disk.normal);
    return 1;
}

/* One slab of the box test: the distances to its near and far planes (picked by the direction's
   sign), kept when they narrow [t_near, t_far]. A zero direction component (inv = +-inf) gives
   +-inf, or NaN with the origin on a plane, which the strict comparisons ignore: the ray then
   misses unless its origin lies within the slab, as when that axis is skipped. The planes are
   picked by the sign bit of d, which is that of inv = 1 / d (a NaN d gives a NaN inv and NaN
   distances either way): GCC still branches on it, but the branch no longer waits for the
   division, so a misprediction (about one slab in six in callgrind's model) resolves sooner. */
static inline void box_slab(const struct prim *p, int axis, double o, double d, double *t_near,
                            int *near_axis, double *t_far, int *far_axis)
{
    const long lo_at = (long)offsetof(struct prim, g.box.lo) + axis * (long)sizeof(double),
               hi_at = (long)offsetof(struct prim, g.box.hi) + axis * (long)sizeof(double);
    const int neg = signbit(d) != 0;
    double near, far;
    memcpy(&near, (const char *)p + (neg ? hi_at : lo_at), sizeof near);
    memcpy(&far, (const char *)p + (neg ? lo_at : hi_at), sizeof far);
    double inv = 1.0 / d;
    double tn = (near - o) * inv, tf = (far - o) * inv;
    if (tn > *t_near)
        *t_near = tn, *near_axis = axis;
    if (tf < *t_far)
        *t_far = tf, *far_axis = axis;
}

/* Axis-aligned box by the slab method (Kay & Kajiya 1986) on the object-space ray, moved there
   in place (no ray copy): the entry face from outside, the exit face from inside. The normal
   is -sign(d) along the face's axis with its zeros signed as set_face signs them (+0 entering,
   -0 leaving: onb_from_w reads the sign of z), then rotated to world space as shape_hit rotates
   other shapes'. */
static __attribute__((noinline)) int hit_box(const struct prim *p, const ray *r, double t_min, double t_max,
                                             struct hit *h)
{
    vec3 o = r->orig, d = r->dir;
    if (p->has_xform) {
        o = rotate_to_object(p, v3_sub(r->orig, p->offset));
        d = rotate_to_object(p, r->dir);
    }
    double t_near = -INFINITY, t_far = INFINITY;
    int near_axis = 0, far_axis = 0;
    box_slab(p, 0, o.x, d.x, &t_near, &near_axis, &t_far, &far_axis);
    box_slab(p, 1, o.y, d.y, &t_near, &near_axis, &t_far, &far_axis);
    box_slab(p, 2, o.z, d.z, &t_near, &near_axis, &t_far, &far_axis);
    if (t_near > t_far)
        return 0;
    int entry = t_near > t_min && t_near < t_max;
    if (!entry && !(t_far > t_min && t_far < t_max))
        return 0;
    double t = entry ? t_near : t_far;
    int axis = entry ? near_axis : far_axis;
    double nv = v3_get(d, axis) > 0 ? -1.0 : 1.0, zero = entry ? 0.0 : -0.0;
    vec3 q = v3_fma(o, d, t);
    vec3 n = v3(axis == 0 ? nv : zero, axis == 1 ? nv : zero, axis == 2 ? nv : zero);
    h->t = t;
    h->front = entry;
    if (p->has_xform) {
        h->p = point_to_world(p, q);
        h->n = rotate_to_world(p, n);
    } else {
        h->p = q;
        h->n = n;
    }
    return 1;
}

/* Capped cylinder about an arbitrary unit axis: the side is the quadric of the distance to the
   axis, restricted to 0 <= height <= H; the caps are disks at both ends. */
static int hit_cylinder(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h)
{
    vec3 a = p->g.cyl.axis;
    double H = p->g.cyl.height, R = p->g.cyl.radius;
    vec3 oc = v3_sub(r->orig, p->g.cyl.base);
    double d_a = v3_dot(r->dir, a), oc_a = v3_dot(oc, a);
    vec3 dp = v3_fma(r->dir, a, -d_a), ocp = v3_fma(oc, a, -oc_a);
    double best = t_max;
    vec3 outward = v3(0, 0, 0);
    double A = v3_len2(dp);
    if (A > 0) {
        double half_b = v3_dot(ocp, dp), c = v3_len2(ocp) - R * R;
        double disc = half_b * half_b - A * c;
        if (disc >= 0) {
            double sq = sqrt(disc);
            double roots[2] = {(-half_b - sq) / A, (-half_b + sq) / A};
            for (int i = 0; i < 2; i++) {
                double t = roots[i], y = oc_a + t * d_a;
                if (t > t_min && t < best && y >= 0 && y <= H) {
                    best = t;
                    outward = v3_scale(v3_fma(ocp, dp, t), 1.0 / R);
                    break;
                }
            }
        }
    }
    if (d_a != 0) {
        for (int cap = 0; cap < 2; cap++) {
            double t = ((cap ? H : 0) - oc_a) / d_a;
            if (t > t_min && t < best && v3_len2(v3_fma(ocp, dp, t)) <= R * R) {
                best = t;
                outward = cap ? a : v3_neg(a);
            }
        }
    }
    if (best >= t_max)
        return 0;
    h->t = best;
    h->p = ray_at(r, best);
    set_face(h, r, outward);
    return 1;
}

/* A sphere whose centre moves linearly with the ray's time (RTOW "The Next Week", ch. 2). */
static __attribute__((noinline)) int hit_moving_sphere(const struct prim *p, const ray *r, double t_min,
                                                       double t_max, struct hit *h)
{
    return hit_sphere(v3_fma(p->g.msphere.center0, p->g.msphere.velocity, r->time), p->g.msphere.radius, r,
                      t_min, t_max, h);
}

/* Moller & Trumbore 1997, "Fast, minimum storage ray-triangle intersection". */
static int hit_triangle(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h)
{
    vec3 e1 = p->g.tri.e1, e2 = p->g.tri.e2;
    vec3 pvec = v3_cross(r->dir, e2);
    double det = v3_dot(e1, pvec);
    if (det == 0)
        return 0;
    double inv = 1.0 / det;
    vec3 tvec = v3_sub(r->orig, p->g.tri.v0);
    double u = v3_dot(tvec, pvec) * inv;
    if (u < 0 || u > 1)
        return 0;
    vec3 qvec = v3_cross(tvec, e1);
    double v = v3_dot(r->dir, qvec) * inv;
    if (v < 0 || u + v > 1)
        return 0;
    double t = v3_dot(e2, qvec) * inv;
    if (!(t > t_min && t < t_max))
        return 0;
    h->t = t;
    h->p = ray_at(r, t);
    set_face(h, r, p->g.tri.normal);
    return 1;
}

uint64_t shape_ray_hash(const ray *r)
{
    return ray_hash_inline(r);
}

void shape_medium_flight(const struct prim *p, const ray *r, uint64_t ray_hash, struct medium_flight *f)
{
    medium_flight_inline(p, r, ray_hash, f);
}

/* A medium's hit at t (out of line: shape_medium_hit then keeps no ray component live across
   its call of log, and spills four values around it instead of ten). */
static __attribute__((noinline)) int medium_scatter(const ray *r, double t, struct hit *h)
{
    h->t = t;
    h->p = ray_at(r, t);
    h->n = v3(1, 0, 0); /* arbitrary: the isotropic phase function ignores it */
    h->front = 1;
    return 1;
}

int shape_medium_hit(const struct prim *p, const ray *r, const struct medium_flight *f, double t_min,
                     double t_max, struct hit *h)
{
    double len = f->len, u = f->u, neg_inv_density = p->g.medium.neg_inv_density;
    /* -log(u) >= 1 - u: when even that bound puts the flight past the span (a margin of 1e-9,
       far above rounding, folded into mean_free_lo), the ray passes through without the log,
       as most do in thin fog. The span inside is at most (t_max - t_min) |dir| (rounding is
       monotone, so this test turns down no ray the span's own would keep), and that test spares
       most rays the boundary's roots. Past the roots the log is taken without the same test on
       the span itself: in final's fog that test went either way (a branch mispredicted on 40%
       of the rays reaching it, after the square root), and the log costs less than the miss. */
    double flight_lo = (1 - u) * p->g.medium.mean_free_lo;
    if (flight_lo > (t_max - t_min) * len)
        return 0;
    double t0, t1;
    if (!sphere_roots(p->g.medium.center, p->g.medium.radius, r, &t0, &t1))
        return 0;
    double enter = t0 > t_min ? t0 : t_min, leave = t1 < t_max ? t1 : t_max;
    if (!(enter < leave))
        return 0;
    double span = (leave - enter) * len;
    double dist = neg_inv_density * log(u);
    if (dist > span)
        return 0;
    return medium_scatter(r, enter + dist / len, h);
}

/* Constant-density medium inside a sphere (RTOW "The Next Week", ch. 9): the ray scatters at
   an exponentially distributed distance while inside, else passes through. */
static int hit_medium(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h)
{
    struct medium_flight f;
    shape_medium_flight(p, r, shape_ray_hash(r), &f);
    return shape_medium_hit(p, r, &f, t_min, t_max, h);
}

/* shape_hit for the rest: boxes, transformed prims, and the types the BVH's leaves test inline
   (out of line: its frame and register saves, for the box's and the cylinder's tests, are not
   paid by the disks and triangles that shape_hit tests itself). */
static __attribute__((noinline)) int hit_other(const struct prim *p, const ray *r, double t_min, double t_max,
                                               struct hit *h)
{
    ray local;
    const ray *q = r;
    if (p->has_xform) { /* the ray in object space */
        local = *r;
        local.orig = rotate_to_object(p, v3_sub(r->orig, p->offset));
        local.dir = rotate_to_object(p, r->dir);
        q = &local;
    }
    int got = 0;
    switch (p->type) {
    case PRIM_SPHERE:
        got = hit_sphere(p->g.sphere.center, p->g.sphere.radius, q, t_min, t_max, h);
        break;
    case PRIM_MOVING_SPHERE:
        got = hit_moving_sphere(p, q, t_min, t_max, h);
        break;
    case PRIM_RECT:
        got = hit_rect(p, q, t_min, t_max, h);
        break;
    case PRIM_DISK:
        got = hit_disk(p, q, t_min, t_max, h);
        break;
    case PRIM_CYLINDER:
        got = hit_cylinder(p, q, t_min, t_max, h);
        break;
    case PRIM_TRIANGLE:
        got = hit_triangle(p, q, t_min, t_max, h);
        break;
    case PRIM_MEDIUM:
        got = hit_medium(p, q, t_min, t_max, h);
        break;
    }
    if (!got)
        return 0;
    if (p->has_xform) {
        h->p = point_to_world(p, h->p);
        h->n = rotate_to_world(p, h->n);
    }
    return 1;
}

int shape_hit(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h)
{
    if (p->type == PRIM_BOX) /* moves the ray to object space itself */
        return hit_box(p, r, t_min, t_max, h);
    if (!p->has_xform) {
        if (p->type == PRIM_DISK)
            return hit_disk(p, r, t_min, t_max, h);
        if (p->type == PRIM_TRIANGLE)
            return hit_triangle(p, r, t_min, t_max, h);
        if (p->type == PRIM_MOVING_SPHERE)
            return hit_moving_sphere(p, r, t_min, t_max, h);
    }
    return hit_other(p, r, t_min, t_max, h);
}
