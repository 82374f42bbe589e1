/* shape_light_inline: a light's sample (its point or cone direction and the density), inline
   for the integrator's light direction (no call, no vectors passed through memory) and for
   shape_light.c's own entry points. Internal to common/. */
#ifndef SHAPE_LIGHT_INLINE_H
#define SHAPE_LIGHT_INLINE_H

#include "shape.h"

#include <float.h>

#include "shape_inline.h"

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

/* A unit direction from o toward light p for s in [0,1)^2 (toward an area-uniform point of a disk
   or rect, or uniform in the cone a sphere subtends: RTOW "The Rest of Your Life", ch. 12;
   uniform over all directions when o is inside the sphere) and, in *pdf, light_pdf's density for
   it, from what the sampling knows (the chosen point's distance, the cone) instead of
   intersecting the ray with p again; it may differ from light_pdf's by rounding. */
static inline __attribute__((always_inline)) vec3 light_sample(const struct prim *p, vec3 o, struct pt2 s,
                                                               double *pdf)
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

/* light_sample for a disk or rect light whose sample point s comes with cos_t and sin_t of
   2 pi s.y (as a pooled set's turns give them): a disk takes its angle from them instead of
   computing it (the same direction up to rounding); a rect ignores them. */
static inline vec3 light_sample_turn(const struct prim *p, vec3 o, struct pt2 s, double cos_t, double sin_t,
                                     double *pdf)
{
    return planar_sample(p, o, light_point_turn(p, s, cos_t, sin_t), pdf);
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
       out, no square root or division for the many directions that miss it; dc |dc| folds the
       sign test in (the right side is > 0), one branch instead of a coin flip and another */
    double dc = v3_dot(dir, to_c);
    if (!(dc * fabs(dc) >= (d2 - r2) * v3_len2(dir)))
        return 0;
    return 1 / (2 * PI * sphere_one_minus_cos(p, o));
}

/* A rect light's pdf by its plane hit (shape_inline.h's rect_plane, hit_rect's test). */
static inline double rect_pdf_hit(const struct prim *p, vec3 o, vec3 dir)
{
    double t;
    if (!rect_plane(p, &o, &dir, HIT_EPS, DBL_MAX, &t))
        return 0;
    return planar_pdf(p, t, v3_at_offset(&dir, p->g.rect.on), dir);
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

/* A disk light's pdf by its plane hit (shape_inline.h's disk_plane, hit_disk's test). */
static inline double disk_pdf_hit(const struct prim *p, vec3 o, vec3 dir)
{
    double t, dn;
    if (!disk_plane(p, o, dir, HIT_EPS, DBL_MAX, &t, &dn))
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

/* sum / n, without the division's latency for one or two lights (a power of two's reciprocal is
   exact, so the product is the quotient bit for bit) */
static inline double lights_mean(double sum, int n)
{
    return n == 1 ? sum : n == 2 ? sum * 0.5 : sum / n;
}

/* A set of lights a strategy samples, each chosen with probability 1 / n: prims[j] is the j-th's
   prim. The mixture's set is every light (light_set_all), next-event estimation's the emitters
   alone (light_set_emitters; scene.h's emitter_lights maps them to their light points): a shadow
   ray toward a non-emitting sample: true object cannot carry light. Two words: passed in
   registers. */
struct light_set {
    const int *prims;
    int n;
};

static inline struct light_set light_set_all(const struct scene *sc)
{
    return (struct light_set){sc->lights, sc->n_lights};
}

static inline struct light_set light_set_emitters(const struct scene *sc)
{
    return (struct light_set){sc->emitters, sc->n_emitters};
}

/* lights_pdf_in from light i of ls on, sum holding the lights before it, light i a disk or rect
   whose cone holds dir (so only its plane hit is left to test). Out of line: reached by a tail
   call only for the few directions inside a planar light's cone. */
static __attribute__((noinline, unused)) double lights_pdf_from(const struct scene *sc, struct light_set ls,
                                                                vec3 o, vec3 dir, int known, double known_pdf,
                                                                int i, double sum)
{
    const struct prim *lp = &sc->prims[ls.prims[i]];
    sum += lp->type == PRIM_DISK ? disk_pdf_hit(lp, o, dir) : rect_pdf_hit(lp, o, dir);
    for (i++; i < ls.n; i++) {
        const struct prim *p = &sc->prims[ls.prims[i]];
        sum += i == known ? known_pdf : light_pdf(p, o, dir);
    }
    return lights_mean(sum, ls.n);
}

/* The density of ls's strategy (a light chosen uniformly, then its sample) for dir from o: the mean
   of its lights' pdfs, the known-th's given as known_pdf (-1: none known). */
static inline __attribute__((always_inline)) double
lights_pdf_in(const struct scene *sc, struct light_set ls, vec3 o, vec3 dir, int known, double known_pdf)
{
    double sum = 0;
    for (int i = 0; i < ls.n; i++) {
        const struct prim *p = &sc->prims[ls.prims[i]];
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
            return lights_pdf_from(sc, ls, o, dir, known, known_pdf, i, sum);
    }
    return lights_mean(sum, ls.n);
}

/* shape_lights_pdf (shape.h): every light's */
static inline __attribute__((always_inline)) double lights_pdf(const struct scene *sc, vec3 o, vec3 dir,
                                                               int known, double known_pdf)
{
    return lights_pdf_in(sc, light_set_all(sc), o, dir, known, known_pdf);
}

#endif
