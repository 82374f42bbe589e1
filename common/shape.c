/* shape: intersection, bounds and light sampling for spheres, axis rects and disks. */
#include "shape.h"

#include <float.h>

/* World -> object space for a rotate_y + translate transform. */
static ray to_object(const struct prim *p, const ray *r)
{
    vec3 o = v3_sub(r->orig, p->offset);
    ray out = *r;
    out.orig = v3(p->cos_y * o.x - p->sin_y * o.z, o.y, p->sin_y * o.x + p->cos_y * o.z);
    out.dir = v3(p->cos_y * r->dir.x - p->sin_y * r->dir.z, r->dir.y,
                 p->sin_y * r->dir.x + p->cos_y * r->dir.z);
    return out;
}

static vec3 rotate_to_world(const struct prim *p, vec3 a)
{
    return v3(p->cos_y * a.x + p->sin_y * a.z, a.y, -p->sin_y * a.x + p->cos_y * a.z);
}

static void set_face(struct hit *h, const ray *r, vec3 outward)
{
    h->front = v3_dot(r->dir, outward) < 0;
    h->n = h->front ? outward : v3_neg(outward);
}

static int hit_sphere(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h)
{
    vec3 c = p->g.sphere.center;
    double rad = p->g.sphere.radius;
    vec3 oc = v3_sub(r->orig, c);
    double a = v3_len2(r->dir);
    double half_b = v3_dot(oc, r->dir);
    double cc = v3_len2(oc) - rad * rad;
    double disc = half_b * half_b - a * cc;
    if (disc < 0)
        return 0;
    double sq = sqrt(disc);
    double t = (-half_b - sq) / a;
    if (t <= t_min || t >= t_max) {
        t = (-half_b + sq) / a;
        if (t <= t_min || t >= t_max)
            return 0;
    }
    h->t = t;
    h->p = ray_at(r, t);
    set_face(h, r, v3_scale(v3_sub(h->p, c), 1.0 / rad));
    return 1;
}

/* The two in-plane axes of a rect whose normal is `axis`. */
static void rect_axes(int axis, int *a, int *b)
{
    *a = axis == 0 ? 1 : 0;
    *b = axis == 2 ? 1 : 2;
}

static int hit_rect(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h)
{
    int ax = p->g.rect.axis, a, b;
    rect_axes(ax, &a, &b);
    double dn = v3_get(r->dir, ax);
    if (dn == 0)
        return 0;
    double t = (p->g.rect.k - v3_get(r->orig, ax)) / dn;
    if (!(t > t_min && t < t_max))
        return 0;
    double pa = v3_get(r->orig, a) + t * v3_get(r->dir, a);
    double pb = v3_get(r->orig, b) + t * v3_get(r->dir, b);
    if (pa < p->g.rect.a0 || pa > p->g.rect.a1 || pb < p->g.rect.b0 || pb > p->g.rect.b1)
        return 0;
    h->t = t;
    h->p = ray_at(r, t);
    h->u = (pa - p->g.rect.a0) / (p->g.rect.a1 - p->g.rect.a0);
    h->v = (pb - p->g.rect.b0) / (p->g.rect.b1 - p->g.rect.b0);
    double s = p->flip ? -1.0 : 1.0;
    vec3 outward = v3(ax == 0 ? s : 0, ax == 1 ? s : 0, ax == 2 ? s : 0);
    set_face(h, r, outward);
    return 1;
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
    h->u = 0.5 + 0.5 * v3_dot(d, p->g.disk.e1) / rad;
    h->v = 0.5 + 0.5 * v3_dot(d, p->g.disk.e2) / rad;
    set_face(h, r, n);
    return 1;
}

int shape_hit(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h)
{
    ray local = p->has_xform ? to_object(p, r) : *r;
    int got = 0;
    switch (p->type) {
    case PRIM_SPHERE:
        got = hit_sphere(p, &local, t_min, t_max, h);
        break;
    case PRIM_RECT:
        got = hit_rect(p, &local, t_min, t_max, h);
        break;
    case PRIM_DISK:
        got = hit_disk(p, &local, t_min, t_max, h);
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

void shape_uv(const struct prim *p, struct hit *h)
{
    if (p->type != PRIM_SPHERE)
        return; /* rect and disk fill u, v while hitting */
    vec3 q = h->p;
    if (p->has_xform) {
        vec3 o = v3_sub(q, p->offset);
        q = v3(p->cos_y * o.x - p->sin_y * o.z, o.y, p->sin_y * o.x + p->cos_y * o.z);
    }
    vec3 d = v3_scale(v3_sub(q, p->g.sphere.center), 1.0 / p->g.sphere.radius);
    double theta = acos(fmax(-1.0, fmin(1.0, -d.y)));
    double phi = atan2(-d.z, d.x) + PI;
    h->u = phi / (2 * PI);
    h->v = theta / PI;
}

static void object_bounds(const struct prim *p, vec3 *lo, vec3 *hi)
{
    switch (p->type) {
    case PRIM_SPHERE: {
        vec3 r = v3(p->g.sphere.radius, p->g.sphere.radius, p->g.sphere.radius);
        *lo = v3_sub(p->g.sphere.center, r);
        *hi = v3_add(p->g.sphere.center, r);
        break;
    }
    case PRIM_RECT: {
        int ax = p->g.rect.axis, a, b;
        rect_axes(ax, &a, &b);
        double l[3], u[3];
        l[ax] = p->g.rect.k - 1e-4;
        u[ax] = p->g.rect.k + 1e-4;
        l[a] = p->g.rect.a0, u[a] = p->g.rect.a1;
        l[b] = p->g.rect.b0, u[b] = p->g.rect.b1;
        *lo = v3(l[0], l[1], l[2]);
        *hi = v3(u[0], u[1], u[2]);
        break;
    }
    case PRIM_DISK: {
        /* Exact box of a disk: extent along axis i is r * sqrt(1 - n_i^2). */
        vec3 n = p->g.disk.normal;
        double r = p->g.disk.radius;
        vec3 e = v3(r * sqrt(fmax(0, 1 - n.x * n.x)) + 1e-4, r * sqrt(fmax(0, 1 - n.y * n.y)) + 1e-4,
                    r * sqrt(fmax(0, 1 - n.z * n.z)) + 1e-4);
        *lo = v3_sub(p->g.disk.center, e);
        *hi = v3_add(p->g.disk.center, e);
        break;
    }
    }
}

void shape_bounds(const struct prim *p, vec3 *lo, vec3 *hi)
{
    vec3 l, h;
    object_bounds(p, &l, &h);
    if (!p->has_xform) {
        *lo = l, *hi = h;
        return;
    }
    vec3 mn = v3(DBL_MAX, DBL_MAX, DBL_MAX), mx = v3(-DBL_MAX, -DBL_MAX, -DBL_MAX);
    for (int i = 0; i < 8; i++) {
        vec3 c = v3(i & 1 ? h.x : l.x, i & 2 ? h.y : l.y, i & 4 ? h.z : l.z);
        vec3 w = v3_add(rotate_to_world(p, c), p->offset);
        mn = v3_min(mn, w);
        mx = v3_max(mx, w);
    }
    *lo = mn, *hi = mx;
}

double shape_area(const struct prim *p)
{
    switch (p->type) {
    case PRIM_RECT:
        return (p->g.rect.a1 - p->g.rect.a0) * (p->g.rect.b1 - p->g.rect.b0);
    case PRIM_DISK:
        return PI * p->g.disk.radius * p->g.disk.radius;
    case PRIM_SPHERE:
        return 4 * PI * p->g.sphere.radius * p->g.sphere.radius;
    }
    return 0;
}

vec3 shape_light_point(const struct prim *p, struct pt2 s)
{
    if (p->type == PRIM_DISK) {
        /* r = R sqrt(u), theta = 2 pi v: uniform by area over the whole radius-R disk. */
        double r = p->g.disk.radius * sqrt(s.x), th = 2 * PI * s.y;
        vec3 q = v3_add(v3_scale(p->g.disk.e1, r * cos(th)), v3_scale(p->g.disk.e2, r * sin(th)));
        return v3_add(p->g.disk.center, q);
    }
    int ax = p->g.rect.axis, a, b;
    rect_axes(ax, &a, &b);
    double c[3];
    c[ax] = p->g.rect.k;
    c[a] = p->g.rect.a0 + s.x * (p->g.rect.a1 - p->g.rect.a0);
    c[b] = p->g.rect.b0 + s.y * (p->g.rect.b1 - p->g.rect.b0);
    return v3(c[0], c[1], c[2]);
}

double shape_light_pdf(const struct prim *p, vec3 o, vec3 dir, double time)
{
    struct hit h;
    ray r = {o, dir, time};
    if (!shape_hit(p, &r, HIT_EPS, DBL_MAX, &h))
        return 0;
    double dist2 = h.t * h.t * v3_len2(dir);
    double cosine = fabs(v3_dot(dir, h.n)) / v3_len(dir);
    if (cosine < 1e-12)
        return 0;
    return dist2 / (cosine * shape_area(p));
}
