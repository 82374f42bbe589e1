/* shape: ray intersection for every primitive type, dispatched by one switch (no function
   pointers per ray); rotate_y + translate move the ray into object space first. */
#include "shape.h"

#include <string.h>

#include "rng.h"
#include "shape_inline.h"

/* World -> object space for a rotate_y + translate transform. */
static ray to_object(const struct prim *p, const ray *r)
{
    vec3 o = v3_sub(r->orig, p->offset);
    ray out = *r;
    out.orig = v3(p->cos_y * o.x - p->sin_y * o.z, o.y, p->sin_y * o.x + p->cos_y * o.z);
    out.dir =
        v3(p->cos_y * r->dir.x - p->sin_y * r->dir.z, r->dir.y, p->sin_y * r->dir.x + p->cos_y * r->dir.z);
    return out;
}

static vec3 rotate_to_world(const struct prim *p, vec3 a)
{
    return v3(p->cos_y * a.x + p->sin_y * a.z, a.y, -p->sin_y * a.x + p->cos_y * a.z);
}

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

void shape_prepare(struct prim *p)
{
    if (p->type == PRIM_RECT) {
        int ax = p->g.rect.axis, a = ax == 0 ? 1 : 0, b = ax == 2 ? 1 : 2;
        p->g.rect.n = v3(ax == 0, ax == 1, ax == 2);
        p->g.rect.ea = v3(a == 0, a == 1, a == 2);
        p->g.rect.eb = v3(b == 0, b == 1, b == 2);
    }
    p->area = shape_area(p);
}

static int hit_disk(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h)
{
    vec3 n = p->g.disk.normal;
    double dn = v3_dot(r->dir, n);
    if (dn == 0)
        return 0;
    double t = v3_dot(v3_sub(p->g.disk.center, r->orig), n) / dn;
    if (!(t > t_min && t < t_max))
        return 0;
    vec3 q = ray_at(r, t);
    vec3 d = v3_sub(q, p->g.disk.center);
    double rad = p->g.disk.radius;
    if (v3_len2(d) > rad * rad)
        return 0;
    h->t = t;
    h->p = q;
    set_face(h, r, n);
    return 1;
}

/* Axis-aligned box by the slab method (Kay & Kajiya 1986): the entry face from outside, the
   exit face from inside; the normal is that face's outward axis. */
static int hit_box(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h)
{
    const double lo[3] = {p->g.box.lo.x, p->g.box.lo.y, p->g.box.lo.z};
    const double hi[3] = {p->g.box.hi.x, p->g.box.hi.y, p->g.box.hi.z};
    const double o[3] = {r->orig.x, r->orig.y, r->orig.z}, d[3] = {r->dir.x, r->dir.y, r->dir.z};
    double t_near = -INFINITY, t_far = INFINITY;
    int near_axis = -1, far_axis = -1;
    for (int a = 0; a < 3; a++) {
        if (d[a] == 0) {
            if (o[a] < lo[a] || o[a] > hi[a])
                return 0;
            continue;
        }
        double inv = 1.0 / d[a];
        double ta = (lo[a] - o[a]) * inv, tb = (hi[a] - o[a]) * inv;
        if (ta > tb) {
            double t = ta;
            ta = tb;
            tb = t;
        }
        if (ta > t_near)
            t_near = ta, near_axis = a;
        if (tb < t_far)
            t_far = tb, far_axis = a;
    }
    if (t_near > t_far)
        return 0;
    double t;
    int axis;
    double sign;
    if (t_near > t_min && t_near < t_max) {
        t = t_near, axis = near_axis, sign = d[axis] > 0 ? -1.0 : 1.0;
    } else if (t_far > t_min && t_far < t_max) {
        t = t_far, axis = far_axis, sign = d[axis] > 0 ? 1.0 : -1.0;
    } else {
        return 0;
    }
    h->t = t;
    h->p = ray_at(r, t);
    set_face(h, r, v3(axis == 0 ? sign : 0, axis == 1 ? sign : 0, axis == 2 ? sign : 0));
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

/* A uniform number in (0, 1] from the ray's bits and the medium's: the same ray always gets
   the same free-flight distance, whatever order the BVH tests primitives in. Each word is
   folded in by a multiply and a shift (every input bit reaches the high half), then one full
   SplitMix64 finaliser: a third of the cost of finalising every word. The ray's words come
   first, so bvh_hit can fold them in once per ray (shape_ray_hash) while it traverses. */
static uint64_t hash_fold(uint64_t h, double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    h = (h ^ bits) * 0x9e3779b97f4a7c15ULL;
    return h ^ (h >> 29);
}

uint64_t shape_ray_hash(const ray *r)
{
    const double in[7] = {r->orig.x, r->orig.y, r->orig.z, r->dir.x, r->dir.y, r->dir.z, r->time};
    uint64_t h = 0x6d656469756dULL;
    for (int i = 0; i < 7; i++)
        h = hash_fold(h, in[i]);
    return h;
}

static double medium_uniform(uint64_t ray_hash, const struct prim *p)
{
    uint64_t h = hash_fold(hash_fold(ray_hash, p->g.medium.radius), p->g.medium.neg_inv_density);
    h = rng_mix64(h);
    return (double)((h >> 11) + 1) * 0x1.0p-53;
}

void shape_medium_flight(const struct prim *p, const ray *r, uint64_t ray_hash, struct medium_flight *f)
{
    f->len = v3_len(r->dir);
    f->u = medium_uniform(ray_hash, p);
}

int shape_medium_hit(const struct prim *p, const ray *r, const struct medium_flight *f, double t_min,
                     double t_max, struct hit *h)
{
    double len = f->len, u = f->u, neg_inv_density = p->g.medium.neg_inv_density;
    /* -log(u) >= 1 - u: when even that bound puts the flight past the span (a margin above
       rounding), the ray passes through without the log, as most do in thin fog. The span
       inside is at most (t_max - t_min) |dir| (rounding is monotone, so this test turns down
       no ray the span's own would keep), and that first test spares most rays the boundary's
       roots; past it, the same test on the span itself. */
    double flight_lo = (1 - u) * -neg_inv_density;
    if (flight_lo > (t_max - t_min) * len * (1 + 1e-9))
        return 0;
    double t0, t1;
    if (!sphere_roots(p->g.medium.center, p->g.medium.radius, r, &t0, &t1))
        return 0;
    double enter = t0 > t_min ? t0 : t_min, leave = t1 < t_max ? t1 : t_max;
    if (!(enter < leave))
        return 0;
    double span = (leave - enter) * len;
    if (flight_lo > span * (1 + 1e-9))
        return 0;
    double dist = neg_inv_density * log(u);
    if (dist > span)
        return 0;
    h->t = enter + dist / len;
    h->p = ray_at(r, h->t);
    h->n = v3(1, 0, 0); /* arbitrary: the isotropic phase function ignores it */
    h->front = 1;
    return 1;
}

/* Constant-density medium inside a sphere (RTOW "The Next Week", ch. 9): the ray scatters at
   an exponentially distributed distance while inside, else passes through. */
static int hit_medium(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h)
{
    struct medium_flight f;
    shape_medium_flight(p, r, shape_ray_hash(r), &f);
    return shape_medium_hit(p, r, &f, t_min, t_max, h);
}

int shape_hit(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h)
{
    ray local;
    const ray *q = r;
    if (p->has_xform) {
        local = to_object(p, r);
        q = &local;
    }
    int got = 0;
    switch (p->type) {
    case PRIM_SPHERE:
        got = hit_sphere(p->g.sphere.center, p->g.sphere.radius, q, t_min, t_max, h);
        break;
    case PRIM_MOVING_SPHERE:
        got = hit_sphere(v3_fma(p->g.msphere.center0, p->g.msphere.velocity, q->time), p->g.msphere.radius, q,
                         t_min, t_max, h);
        break;
    case PRIM_RECT:
        got = hit_rect(p, q, t_min, t_max, h);
        break;
    case PRIM_DISK:
        got = hit_disk(p, q, t_min, t_max, h);
        break;
    case PRIM_BOX:
        got = hit_box(p, q, t_min, t_max, h);
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
        h->p = v3_add(rotate_to_world(p, h->p), p->offset);
        h->n = rotate_to_world(p, h->n);
    }
    return 1;
}
