/* shape_light: bounds, surface coordinates, and the light sampling of spheres (cone), disks and
   rects (area-uniform points), with the matching solid-angle densities. */
#include "shape.h"

#include <float.h>

#include "shape_inline.h"

void shape_uv(const struct prim *p, struct hit *h)
{
    vec3 q = h->p;
    if (p->has_xform) {
        vec3 o = v3_sub(q, p->offset);
        q = v3(p->cos_y * o.x - p->sin_y * o.z, o.y, p->sin_y * o.x + p->cos_y * o.z);
    }
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
    double theta = acos(fmax(-1.0, fmin(1.0, -d.y)));
    double phi = atan2(-d.z, d.x) + PI;
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
        vec3 w = v3_add(rotate_to_world(p, c), p->offset);
        *lo = v3_sub(w, v3(r, r, r)), *hi = v3_add(w, v3(r, r, r));
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

int shape_light_uses_points(const struct prim *p)
{
    return p->type == PRIM_DISK || p->type == PRIM_RECT;
}

/* The point of light p for s: a disk's at angle 2 pi s.y, whose cos and sin are given. */
static inline vec3 light_point_turn(const struct prim *p, struct pt2 s, double cos_t, double sin_t)
{
    if (p->type == PRIM_DISK) {
        /* r = R sqrt(u), theta = 2 pi v: uniform by area over the whole radius-R disk. */
        double r = p->g.disk.radius * sqrt(s.x);
        vec3 q = v3_add(v3_scale(p->g.disk.e1, r * cos_t), v3_scale(p->g.disk.e2, r * sin_t));
        return v3_add(p->g.disk.center, q);
    }
    /* the unit axes have one non-zero component each: the sum is exact */
    double pa = p->g.rect.a0 + s.x * (p->g.rect.a1 - p->g.rect.a0);
    double pb = p->g.rect.b0 + s.y * (p->g.rect.b1 - p->g.rect.b0);
    return v3_add(v3_add(v3_scale(p->g.rect.n, p->g.rect.k), v3_scale(p->g.rect.ea, pa)),
                  v3_scale(p->g.rect.eb, pb));
}

static inline vec3 light_point(const struct prim *p, struct pt2 s)
{
    double sin_t = 0, cos_t = 0;
    if (p->type == PRIM_DISK)
        v3_sincos_turn(s.y, &sin_t, &cos_t);
    return light_point_turn(p, s, cos_t, sin_t);
}

vec3 shape_light_point(const struct prim *p, struct pt2 s)
{
    return light_point(p, s);
}

/* 1 - cos of the half-angle of the cone a sphere subtends from o, computed without
   cancellation for far spheres; 2 (the whole sphere of directions) when o is inside. */
static inline double sphere_one_minus_cos(const struct prim *p, vec3 o)
{
    double d2 = v3_len2(v3_sub(p->g.sphere.center, o)), r2 = p->g.sphere.radius * p->g.sphere.radius;
    if (d2 <= r2)
        return 2;
    double s2 = r2 / d2; /* sin^2 of the half-angle */
    return s2 / (1 + sqrt(1 - s2));
}

/* A direction uniform in the cone sphere p subtends from o; *omc is that cone's 1 - cos. */
static inline __attribute__((always_inline)) vec3 sphere_cone_dir(const struct prim *p, vec3 o, struct pt2 s,
                                                                  double *omc)
{
    /* z uniform in [cos_max, 1] is uniform over the cone's solid angle. */
    *omc = sphere_one_minus_cos(p, o);
    double z = 1 - s.y * *omc, sin_phi, cos_phi;
    double sin_t = sqrt(d_max(0, 1 - z * z));
    v3_sincos_turn(s.x, &sin_phi, &cos_phi);
    vec3 to_c = v3_sub(p->g.sphere.center, o);
    double len = v3_len(to_c);
    onb f = onb_from_w(len > 0 ? v3_scale(to_c, 1.0 / len) : v3(0, 0, 1));
    return onb_local(&f, v3(cos_phi * sin_t, sin_phi * sin_t, z));
}

vec3 shape_light_dir(const struct prim *p, vec3 o, struct pt2 s)
{
    double omc;
    if (p->type != PRIM_SPHERE)
        return v3_sub(shape_light_point(p, s), o);
    return sphere_cone_dir(p, o, s, &omc);
}

/* Solid-angle density of area-uniform sampling of a planar light seen at distance t along dir
   with dn = dir . normal: dist^2 / (cos area) = t^2 |dir|^3 / (|dn| area). Lights are sampled
   from both sides (the back is dark, and the estimate then just adds nothing). */
static inline double planar_pdf(const struct prim *p, double t, double dn, vec3 dir)
{
    double d2 = v3_len2(dir), adn = fabs(dn);
    if (!(adn > 1e-12 * sqrt(d2)))
        return 0;
    return t * t * d2 * sqrt(d2) / (adn * p->area);
}

static inline double sphere_pdf(const struct prim *p, vec3 o, vec3 dir)
{
    vec3 to_c = v3_sub(p->g.sphere.center, o);
    double d2 = v3_len2(to_c), r2 = p->g.sphere.radius * p->g.sphere.radius;
    if (d2 <= r2)
        return 1 / (4 * PI); /* o inside: uniform over all directions */
    /* in the cone iff cos(dir, to_c) >= cos_max = sqrt(1 - r2 / d2): squared and multiplied
       out, no square root or division for the many directions that miss it */
    double dc = v3_dot(dir, to_c);
    if (!(dc > 0 && dc * dc >= (d2 - r2) * v3_len2(dir)))
        return 0;
    return 1 / (2 * PI * sphere_one_minus_cos(p, o));
}

/* shape_hit's rect test, minus the hit record */
static inline double rect_pdf_hit(const struct prim *p, vec3 o, vec3 dir)
{
    const vec3 n = p->g.rect.n;
    double dn = v3_dot(dir, n), t = (p->g.rect.k - v3_dot(o, n)) / dn;
    if (!(t > HIT_EPS && t < DBL_MAX))
        return 0;
    vec3 q = v3_fma(o, dir, t);
    double pa = v3_dot(q, p->g.rect.ea), pb = v3_dot(q, p->g.rect.eb);
    if (pa < p->g.rect.a0 || pa > p->g.rect.a1 || pb < p->g.rect.b0 || pb > p->g.rect.b1)
        return 0;
    return planar_pdf(p, t, dn, dir);
}

/* Most directions miss a planar light: reject those outside the cone of its bounding ball c, r2
   (a disk's centre and radius R; a rect's centre and half diagonal), o outside it, with squares
   only, before the plane hit's division and the unpredictable "plane ahead" branch. The margins
   (1e-6 on R^2 for "outside", 1e-9 of d2 on the cone, and 1e-9 of a rect's R^2 for the rounding
   of its centre and diagonal) are far above rounding, so the test never rejects a direction the
   plane hit would accept. */
static inline __attribute__((always_inline)) int ball_cone(vec3 c, double r2, double r2_out, vec3 o, vec3 dir)
{
    const vec3 to_c = v3_sub(c, o);
    double d2 = v3_len2(to_c);
    if (!(d2 > r2_out))
        return 1;
    double dc = v3_dot(dir, to_c); /* dc |dc|: one branch rejects dc <= 0 too */
    return dc * fabs(dc) >= (d2 * (1 - 1e-9) - r2) * v3_len2(dir);
}

static inline __attribute__((always_inline)) int disk_in_cone(const struct prim *p, vec3 o, vec3 dir)
{
    return ball_cone(p->g.disk.center, p->g.disk.r2, p->g.disk.r2_out, o, dir);
}

static inline __attribute__((always_inline)) int rect_in_cone(const struct prim *p, vec3 o, vec3 dir)
{
    return ball_cone(p->g.rect.ball_c, p->g.rect.ball_r2, p->g.rect.ball_r2_out, o, dir);
}

static inline double rect_pdf(const struct prim *p, vec3 o, vec3 dir)
{
    return rect_in_cone(p, o, dir) ? rect_pdf_hit(p, o, dir) : 0;
}

/* A disk light's pdf by its plane hit. */
static inline double disk_pdf_hit(const struct prim *p, vec3 o, vec3 dir)
{
    const vec3 n = p->g.disk.normal, to_c = v3_sub(p->g.disk.center, o);
    double dn = v3_dot(dir, n), t = v3_dot(to_c, n) / dn;
    if (!(t > HIT_EPS && t < DBL_MAX))
        return 0;
    vec3 d = v3_sub(v3_fma(o, dir, t), p->g.disk.center);
    if (v3_len2(d) > p->g.disk.r2)
        return 0;
    return planar_pdf(p, t, dn, dir);
}

static inline __attribute__((always_inline)) double disk_pdf(const struct prim *p, vec3 o, vec3 dir)
{
    return disk_in_cone(p, o, dir) ? disk_pdf_hit(p, o, dir) : 0;
}

/* One light's pdf, inline so shape_lights_pdf's loop has no call per light (forced: with two
   callers GCC keeps it out of line, which cost 2-3% of the instructions of every scene). */
static inline __attribute__((always_inline)) double light_pdf(const struct prim *p, vec3 o, vec3 dir)
{
    switch (p->type) {
    case PRIM_SPHERE:
        return sphere_pdf(p, o, dir);
    case PRIM_RECT:
        return rect_pdf(p, o, dir);
    case PRIM_DISK:
        return disk_pdf(p, o, dir);
    default:
        return 0;
    }
}

double shape_light_pdf(const struct prim *p, vec3 o, vec3 dir, double time)
{
    (void)time;
    return light_pdf(p, o, dir);
}

/* The unit direction from o to the chosen point q of a planar light and its pdf: q is at
   distance len, so dist^2 / (cos area) = len^3 / (|to_q . n| area), no plane to intersect
   (planar_pdf's edge-on guard with |dir| = 1). */
static inline vec3 planar_sample(const struct prim *p, vec3 o, vec3 q, double *pdf)
{
    vec3 to_q = v3_sub(q, o);
    double len2 = v3_len2(to_q), len = sqrt(len2);
    vec3 dir = v3_scale(to_q, 1.0 / len);
    double qn = fabs(v3_dot(to_q, p->type == PRIM_DISK ? p->g.disk.normal : p->g.rect.n));
    *pdf = len > HIT_EPS && qn > 1e-12 * len ? len2 * len / (qn * p->area) : 0;
    return dir;
}

vec3 shape_light_sample(const struct prim *p, vec3 o, struct pt2 s, double *pdf)
{
    if (p->type == PRIM_SPHERE) {
        double omc;
        /* unit by construction (a unit vector in an orthonormal frame), to rounding: not made
           unit again, a square root and a division off the light sample's dependency chain */
        vec3 dir = sphere_cone_dir(p, o, s, &omc);
        *pdf = 1 / (2 * PI * omc); /* omc = 2 inside: 1 / (4 pi), uniform over all directions */
        return dir;
    }
    return planar_sample(p, o, light_point(p, s), pdf);
}

vec3 shape_light_sample_turn(const struct prim *p, vec3 o, struct pt2 s, double cos_t, double sin_t,
                             double *pdf)
{
    return planar_sample(p, o, light_point_turn(p, s, cos_t, sin_t), pdf);
}

/* sum / n, without the division's latency for one or two lights (a power of two's reciprocal is
   exact, so the product is the quotient bit for bit) */
static inline double lights_mean(double sum, int n)
{
    return n == 1 ? sum : n == 2 ? sum * 0.5 : sum / n;
}

/* shape_lights_pdf from light i on, sum holding the lights before it (out of line: reached by a
   tail call only for the few directions inside a planar light's cone). */
static __attribute__((noinline)) double lights_pdf_from(const struct scene *sc, vec3 o, vec3 dir, int known,
                                                        double known_pdf, int i, double sum)
{
    for (; i < sc->n_lights; i++) {
        const struct prim *p = &sc->prims[sc->lights[i]];
        sum += i == known ? known_pdf : light_pdf(p, o, dir);
    }
    return lights_mean(sum, sc->n_lights);
}

double shape_lights_pdf(const struct scene *sc, vec3 o, vec3 dir, int known, double known_pdf)
{
    double sum = 0;
    for (int i = 0; i < sc->n_lights; i++) {
        const struct prim *p = &sc->prims[sc->lights[i]];
        int in_cone;
        if (i == known) {
            sum += known_pdf;
            continue;
        } else if (p->type == PRIM_DISK) {
            in_cone = disk_in_cone(p, o, dir);
        } else if (p->type == PRIM_RECT) {
            in_cone = rect_in_cone(p, o, dir);
        } else {
            sum += light_pdf(p, o, dir);
            continue;
        }
        /* a planar light's plane hit and whatever follows, out of this loop: without a call to
           return here, the loop keeps its values in registers (a light outside its cone adds 0:
           sum is unchanged) */
        if (in_cone)
            return lights_pdf_from(sc, o, dir, known, known_pdf, i, sum);
    }
    return lights_mean(sum, sc->n_lights);
}
