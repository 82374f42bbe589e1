/* shape_light: bounds, surface coordinates, and the light sampling of spheres (cone), disks and
   rects (area-uniform points), with the matching solid-angle densities. */
#include "shape.h"

#include <float.h>

#include "shape_inline.h"
#include "shape_light_inline.h"

void shape_uv(const struct prim *p, struct hit *h)
{
    vec3 q = h->p;
    if (p->has_xform)
        q = rotate_to_object(p, v3_sub(q, p->offset));
    if (p->type == PRIM_RECT) {
        h->u = (v3_dot(q, p->g.rect.ea) - p->g.rect.a0) / (p->g.rect.a1 - p->g.rect.a0);
        h->v = (v3_dot(q, p->g.rect.eb) - p->g.rect.b0) / (p->g.rect.b1 - p->g.rect.b0);
        return;
    }
    if (p->type == PRIM_DISK) {
        vec3 d = v3_sub(q, p->g.disk.center);
        h->u = 0.5 + 0.5 * v3_dot(d, p->g.disk.e1) / p->g.disk.radius;
        h->v = 0.5 + 0.5 * v3_dot(d, p->g.disk.e2) / p->g.disk.radius;
        return;
    }
    if (p->type != PRIM_SPHERE)
        return; /* other shapes carry no texture image */
    vec3 d = v3_scale(v3_sub(q, p->g.sphere.center), 1.0 / p->g.sphere.radius);
    /* acos(-d.y) as the angle of (|(d.x, d.z)|, -d.y): no clamp of d.y to [-1, 1] needed */
    double theta = d_atan2(sqrt(d.x * d.x + d.z * d.z), -d.y);
    double phi = d_atan2(-d.z, d.x) + PI;
    h->u = phi / (2 * PI);
    h->v = theta / PI;
}

static void sphere_box(vec3 c, double r, vec3 *lo, vec3 *hi)
{
    *lo = v3_sub(c, v3(r, r, r));
    *hi = v3_add(c, v3(r, r, r));
}

/* Exact box of a disk of radius r about unit normal n: extent along axis i is r sqrt(1 - n_i^2). */
static vec3 disk_extent(vec3 n, double r)
{
    return v3(r * sqrt(fmax(0, 1 - n.x * n.x)) + 1e-4, r * sqrt(fmax(0, 1 - n.y * n.y)) + 1e-4,
              r * sqrt(fmax(0, 1 - n.z * n.z)) + 1e-4);
}

static void object_bounds(const struct prim *p, vec3 *lo, vec3 *hi)
{
    switch (p->type) {
    case PRIM_SPHERE:
        sphere_box(p->g.sphere.center, p->g.sphere.radius, lo, hi);
        break;
    case PRIM_MEDIUM:
        sphere_box(p->g.medium.center, p->g.medium.radius, lo, hi);
        break;
    case PRIM_MOVING_SPHERE: {
        vec3 l0, h0, l1, h1;
        const double r = p->g.msphere.radius;
        sphere_box(v3_fma(p->g.msphere.center0, p->g.msphere.velocity, p->g.msphere.time_lo), r, &l0, &h0);
        sphere_box(v3_fma(p->g.msphere.center0, p->g.msphere.velocity, p->g.msphere.time_hi), r, &l1, &h1);
        *lo = v3_min(l0, l1);
        *hi = v3_max(h0, h1);
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
        vec3 e = disk_extent(p->g.disk.normal, p->g.disk.radius);
        *lo = v3_sub(p->g.disk.center, e);
        *hi = v3_add(p->g.disk.center, e);
        break;
    }
    case PRIM_BOX:
        *lo = p->g.box.lo;
        *hi = p->g.box.hi;
        break;
    case PRIM_CYLINDER: {
        /* The union of the two cap disks' boxes encloses the whole cylinder. */
        vec3 e = disk_extent(p->g.cyl.axis, p->g.cyl.radius);
        vec3 top = v3_fma(p->g.cyl.base, p->g.cyl.axis, p->g.cyl.height);
        *lo = v3_sub(v3_min(p->g.cyl.base, top), e);
        *hi = v3_add(v3_max(p->g.cyl.base, top), e);
        break;
    }
    case PRIM_TRIANGLE: {
        vec3 a = p->g.tri.v0, b = v3_add(a, p->g.tri.e1), c = v3_add(a, p->g.tri.e2);
        vec3 pad = v3(1e-4, 1e-4, 1e-4);
        *lo = v3_sub(v3_min(a, v3_min(b, c)), pad);
        *hi = v3_add(v3_max(a, v3_max(b, c)), pad);
        break;
    }
    default:
        *lo = *hi = v3(0, 0, 0);
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
    if (p->type == PRIM_SPHERE || p->type == PRIM_MEDIUM) {
        /* a sphere that keeps its transform (a medium's boundary, an image-textured sphere):
           its moved centre +- radius, not the box of its rotated bounding cube (22% wider in x
           and z at 15 degrees) */
        vec3 c = p->type == PRIM_SPHERE ? p->g.sphere.center : p->g.medium.center;
        double r = p->type == PRIM_SPHERE ? p->g.sphere.radius : p->g.medium.radius;
        vec3 w = point_to_world(p, c);
        *lo = v3_sub(w, v3(r, r, r)), *hi = v3_add(w, v3(r, r, r));
        return;
    }
    vec3 mn = v3(DBL_MAX, DBL_MAX, DBL_MAX), mx = v3(-DBL_MAX, -DBL_MAX, -DBL_MAX);
    for (int i = 0; i < 8; i++) {
        vec3 c = v3(i & 1 ? h.x : l.x, i & 2 ? h.y : l.y, i & 4 ? h.z : l.z);
        vec3 w = point_to_world(p, c);
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

int shape_light_uses_points(const struct prim *p)
{
    return p->type == PRIM_DISK || p->type == PRIM_RECT;
}

double shape_lights_pdf(const struct scene *sc, vec3 o, vec3 dir, int known, double known_pdf)
{
    return lights_pdf(sc, o, dir, known, known_pdf);
}
