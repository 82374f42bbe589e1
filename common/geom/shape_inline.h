/* shape_inline: the sphere and rect tests, inline for the BVH's leaves (no call, no type
   switch for the two commonest primitives) and for shape_hit. Internal to common/. */
#ifndef SHAPE_INLINE_H
#define SHAPE_INLINE_H

#include "geom_types.h"

#include <string.h>

#include "base/rng.h"

/* A rotate_y's turn of object-space vector a into world space, and back. */
static inline vec3 rotate_to_world(const struct prim *p, vec3 a)
{
    return v3(p->cos_y * a.x + p->sin_y * a.z, a.y, -p->sin_y * a.x + p->cos_y * a.z);
}
static inline vec3 rotate_to_object(const struct prim *p, vec3 a)
{
    return v3(p->cos_y * a.x - p->sin_y * a.z, a.y, p->sin_y * a.x + p->cos_y * a.z);
}

/* rotate_y + translate of an object-space point (directions take rotate_to_world alone). */
static inline vec3 point_to_world(const struct prim *p, vec3 a)
{
    return v3_add(rotate_to_world(p, a), p->offset);
}

/* The in-plane axes a, b of a rect whose normal is axis (yz: y, z; xz: x, z; xy: x, y). */
static inline void rect_axes(int axis, int *a, int *b)
{
    *a = axis == 0 ? 1 : 0;
    *b = axis == 2 ? 1 : 2;
}

static inline void set_face(struct hit *h, const ray *r, vec3 outward)
{
    h->front = v3_dot(r->dir, outward) < 0;
    h->n = h->front ? outward : v3_neg(outward);
}

/* The line o + t d against the sphere |p - c| = rad: a = |d|^2, half_b = (o - c).d and the
   square root of the discriminant, so the roots are (-half_b -+ sq) / a. 0 when it misses. */
static inline int sphere_quadratic(vec3 c, double rad, const ray *r, double *a, double *half_b, double *sq)
{
    vec3 oc = v3_sub(r->orig, c);
    *a = v3_len2(r->dir);
    *half_b = v3_dot(oc, r->dir);
    double cc = v3_len2(oc) - rad * rad;
    double disc = *half_b * *half_b - *a * cc;
    if (disc < 0 || *a == 0)
        return 0;
    *sq = sqrt(disc);
    return 1;
}

/* The roots are compared as a t (a = |d|^2 > 0) and divided only for a hit. Always inline, as
   hit_rect: bvh.c's two traversals each keep their own copy in the leaf loop (with two callers
   GCC's unit growth limit would put one out of line). */
static inline __attribute__((always_inline)) int hit_sphere(vec3 c, double rad, const ray *r, double t_min,
                                                            double t_max, struct hit *h)
{
    double a, half_b, sq;
    if (!sphere_quadratic(c, rad, r, &a, &half_b, &sq))
        return 0;
    double lo = t_min * a, hi = t_max * a;
    double at = -half_b - sq;
    if (!(at > lo && at < hi)) {
        at = -half_b + sq;
        if (!(at > lo && at < hi))
            return 0;
    }
    h->t = at / a;
    h->p = ray_at(r, h->t);
    set_face(h, r, v3_scale(v3_sub(h->p, c), 1.0 / rad));
    return 1;
}

/* Component of v at byte offset off (a rect's on, oa, ob): one load, no branch on the axis. */
static inline double v3_at_offset(const vec3 *v, long off)
{
    double x;
    memcpy(&x, (const char *)v + off, sizeof x);
    return x;
}

/* The rect's plane test, written once for hit_rect and a rect light's pdf (shape_light_inline.h's
   rect_pdf_hit; packet.c's rect4 is its vector form, tested bit for bit against hit_rect): 1 when
   the line o + t dir meets the rect at *t in (t_min, t_max). The plane's distance and the hit's
   in-plane coordinates read the components on the rect's axes by their offsets: no branch on the
   axis, and the same values the dot products with the unit axes give (x 1 + y 0 + z 0 is x up to
   the sign of a zero, which no comparison sees). A direction parallel to the plane gives t = +-inf
   or NaN, which the range test turns down. */
static inline __attribute__((always_inline)) int
rect_plane(const struct prim *p, const vec3 *o, const vec3 *dir, double t_min, double t_max, double *t)
{
    const long on = p->g.rect.on, oa = p->g.rect.oa, ob = p->g.rect.ob;
    const double tt = (p->g.rect.k - v3_at_offset(o, on)) / v3_at_offset(dir, on);
    *t = tt;
    if (!(tt > t_min && tt < t_max))
        return 0;
    double pa = v3_at_offset(o, oa) + v3_at_offset(dir, oa) * tt;
    double pb = v3_at_offset(o, ob) + v3_at_offset(dir, ob) * tt;
    return !(pa < p->g.rect.a0 || pa > p->g.rect.a1 || pb < p->g.rect.b0 || pb > p->g.rect.b1);
}

static inline __attribute__((always_inline)) int hit_rect(const struct prim *p, const ray *r, double t_min,
                                                          double t_max, struct hit *h)
{
    double t;
    if (!rect_plane(p, &r->orig, &r->dir, t_min, t_max, &t))
        return 0;
    h->t = t;
    h->p = ray_at(r, t);
    set_face(h, r, p->flip ? v3_neg(p->g.rect.n) : p->g.rect.n);
    return 1;
}

/* The disk's plane test, written once for shape.c's hit_disk and a disk light's pdf
   (disk_pdf_hit; packet.c's disk4 is its vector form): 1 when the line o + t dir meets the disk
   at *t in (t_min, t_max), *dn = dir . normal. A direction parallel to the plane (dn 0) gives
   t = +-inf or NaN, which the range test turns down. */
static inline __attribute__((always_inline)) int disk_plane(const struct prim *p, vec3 o, vec3 dir,
                                                            double t_min, double t_max, double *t, double *dn)
{
    const vec3 n = p->g.disk.normal;
    const double d_n = v3_dot(dir, n), tt = v3_dot(v3_sub(p->g.disk.center, o), n) / d_n;
    *t = tt, *dn = d_n;
    if (!(tt > t_min && tt < t_max))
        return 0;
    return !(v3_len2(v3_sub(v3_fma(o, dir, tt), p->g.disk.center)) > p->g.disk.r2);
}

/* A uniform number in (0, 1] from the ray's bits and the medium's: the same ray always gets
   the same free-flight distance, whatever order the BVH tests primitives in. Each word is
   multiplied by its own odd constant and the products summed (independent multiplies, not a
   serial chain: distinct rays differing in one word always differ in the sum), then one
   SplitMix64 finaliser mixes every bit. The ray's part comes first, so bvh_hit can start it
   once per ray (ray_hash_inline; shape_ray_hash out of line) while it traverses. */
static inline uint64_t hash_word(double x, uint64_t k)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    return bits * k;
}

static inline uint64_t ray_hash_inline(const ray *r)
{
    return (hash_word(r->orig.x, 0x9e3779b97f4a7c15ULL) + hash_word(r->orig.y, 0xbf58476d1ce4e5b9ULL)) +
           (hash_word(r->orig.z, 0x94d049bb133111ebULL) + hash_word(r->dir.x, 0xd1b54a32d192ed03ULL)) +
           ((hash_word(r->dir.y, 0xff51afd7ed558ccdULL) + hash_word(r->dir.z, 0xc4ceb9fe1a85ec53ULL)) +
            hash_word(r->time, 0x2545f4914f6cdd1dULL));
}

/* The medium's two words of the hash (shape_prepare keeps it in the prim). */
static inline uint64_t medium_hash_key(const struct prim *p)
{
    return hash_word(p->g.medium.radius, 0x5851f42d4c957f2dULL) +
           hash_word(p->g.medium.neg_inv_density, 0xda942042e4dd58b5ULL);
}

static inline double medium_uniform(uint64_t ray_hash, const struct prim *p)
{
    uint64_t h = rng_mix64(ray_hash + p->g.medium.hash_key);
    return (double)((h >> 11) + 1) * 0x1.0p-53;
}

static inline void medium_flight_inline(const struct prim *p, const ray *r, uint64_t ray_hash,
                                        struct medium_flight *f)
{
    f->len = v3_len(r->dir);
    f->u = medium_uniform(ray_hash, p);
}

#endif
