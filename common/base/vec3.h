/* vec3: small value-struct vector math, all static inline (the renderer's hot path). */
#ifndef VEC3_H
#define VEC3_H

#include <math.h>
#include <stdint.h>

#define PI 3.14159265358979323846

typedef struct {
    double x, y, z;
} vec3;

typedef struct {
    vec3 orig, dir;
    double time;
} ray;

static inline vec3 v3(double x, double y, double z)
{
    return (vec3){x, y, z};
}
static inline vec3 v3_add(vec3 a, vec3 b)
{
    return v3(a.x + b.x, a.y + b.y, a.z + b.z);
}
static inline vec3 v3_sub(vec3 a, vec3 b)
{
    return v3(a.x - b.x, a.y - b.y, a.z - b.z);
}
static inline vec3 v3_mul(vec3 a, vec3 b)
{
    return v3(a.x * b.x, a.y * b.y, a.z * b.z);
}
static inline vec3 v3_scale(vec3 a, double s)
{
    return v3(a.x * s, a.y * s, a.z * s);
}
static inline vec3 v3_neg(vec3 a)
{
    return v3(-a.x, -a.y, -a.z);
}
static inline double v3_dot(vec3 a, vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static inline vec3 v3_cross(vec3 a, vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double v3_len2(vec3 a)
{
    return v3_dot(a, a);
}
static inline double v3_len(vec3 a)
{
    return sqrt(v3_dot(a, a));
}
static inline vec3 v3_unit(vec3 a)
{
    return v3_scale(a, 1.0 / v3_len(a));
}
static inline vec3 v3_fma(vec3 a, vec3 b, double s)
{
    return v3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s);
}
static inline double v3_get(vec3 a, int axis)
{
    return axis == 0 ? a.x : axis == 1 ? a.y : a.z;
}
/* min and max without libm's fmin/fmax calls (no -ffast-math here, so those are not inlined);
   unlike them these return b when a is NaN. */
static inline double d_min(double a, double b)
{
    return a < b ? a : b;
}
static inline double d_max(double a, double b)
{
    return a > b ? a : b;
}
static inline vec3 v3_min(vec3 a, vec3 b)
{
    return v3(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z));
}
static inline vec3 v3_max(vec3 a, vec3 b)
{
    return v3(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z));
}
static inline int v3_finite(vec3 a)
{
    return isfinite(a.x) && isfinite(a.y) && isfinite(a.z);
}
static inline vec3 ray_at(const ray *r, double t)
{
    return v3_fma(r->orig, r->dir, t);
}

static inline vec3 v3_reflect(vec3 v, vec3 n)
{
    return v3_sub(v, v3_scale(n, 2 * v3_dot(v, n)));
}
static inline vec3 v3_refract(vec3 uv, vec3 n, double etai_over_etat)
{
    double cos_theta = d_min(v3_dot(v3_neg(uv), n), 1.0);
    vec3 perp = v3_scale(v3_fma(uv, n, cos_theta), etai_over_etat);
    vec3 para = v3_scale(n, -sqrt(fabs(1.0 - v3_len2(perp))));
    return v3_add(perp, para);
}

/* sin and cos of 2 pi u for u in [0, 1] (angles in turns, as samplers draw them): reduced to a
   quarter turn and shifted to [-pi/4, pi/4], where Taylor series through x^15 and x^16 are
   exact to 5e-17; then rotated back by the quarter turns. Branch-free, about a third of the
   cost of libm's sincos, which the direction sampling would otherwise call on every bounce. */
static inline void v3_sincos_turn(double u, double *s, double *c)
{
    double x4 = 4 * u;
    int q = (int)x4; /* u >= 0: truncation is floor */
    double x = (x4 - q - 0.5) * (PI / 2), y = x * x, y2 = y * y, y4 = y2 * y2;
    /* both series in y = x^2 by Estrin's scheme: pairs, then pairs of pairs, a dependency
       chain of ~4 multiplies instead of Horner's 8 (the same terms, summed in another order) */
    double sn = x * ((1 + y * (-1.0 / 6)) + y2 * (1.0 / 120 + y * (-1.0 / 5040)) +
                     y4 * ((1.0 / 362880 + y * (-1.0 / 39916800)) +
                           y2 * (1.0 / 6227020800 + y * (-1.0 / 1307674368000))));
    double cs =
        (1 + y * (-1.0 / 2)) + y2 * (1.0 / 24 + y * (-1.0 / 720)) +
        y4 * ((1.0 / 40320 + y * (-1.0 / 3628800)) + y2 * (1.0 / 479001600 + y * (-1.0 / 87178291200))) +
        y4 * y4 * (1.0 / 20922789888000);
    const double half_sqrt2 = 0.70710678118654752440;
    double s0 = (sn + cs) * half_sqrt2, c0 = (cs - sn) * half_sqrt2; /* of x + pi/4 */
    double s1 = q & 1 ? c0 : s0, c1 = q & 1 ? -s0 : c0;              /* a quarter turn on */
    *s = q & 2 ? -s1 : s1;
    *c = q & 2 ? -c1 : c1;
}

/* sin x without libm, for |x| < 2^40 (libm's beyond): x in turns, its fraction by sincos_turn.
   x / (2 pi) rounds once, which moves the angle by up to |x| 2^-53, and a negative fraction
   wraps to 1 + u, which holds u to 2^-53 absolute: within 1e-15 + 2e-16 |x| of sin x. The
   marble's stripes took libm's (0.6% of final's time, mostly the call). */
static inline double d_sin(double x)
{
    double u = x * (1 / (2 * PI));
    if (!(fabs(u) < 0x1.0p40))
        return sin(x);
    u -= (double)(int64_t)u; /* in (-1, 1) */
    u += u < 0 ? 1 : 0;
    double s, c;
    v3_sincos_turn(u, &s, &c);
    return s;
}

/* atan2(y, x) without libm, for finite y and x (signed zeros as libm's): within 1e-15 of it.
   t = min / max of |x| and |y| in [0, 1]; past tan(pi/8), atan t = pi/4 + atan((t - 1) / (t + 1)),
   the quotient taken of min - max and min + max (one division either way); then
   atan t = t p(t^2) for |t| <= tan(pi/8), p a degree-10 Chebyshev fit of atan(sqrt z) / sqrt z
   (relative error 3.5e-17), and the octant's reflections. The earth's (u, v) took libm's acos,
   atan2, fmin and fmax (0.9% of final's time). */
static inline double d_atan2(double y, double x)
{
    const double ax = fabs(x), ay = fabs(y);
    const int swap = ay > ax;
    const double lo = swap ? ax : ay, hi = swap ? ay : ax;
    const int past = lo > 0.41421356237309504880 * hi;
    /* halved near DBL_MAX, where lo + hi would overflow (exactly: by 1 elsewhere, nothing moves) */
    const double k = hi > 0x1p1022 ? 0.5 : 1;
    const double num = past ? lo * k - hi * k : lo, den = past ? lo * k + hi * k : hi;
    const double t = den > 0 ? num / den : 0, z = t * t, z2 = z * z, z4 = z2 * z2, z8 = z4 * z4;
    const double p =
        ((0.99999999999999996532 + z * -0.333333333333284385718) +
         z2 * (0.199999999988551101336 + z * -0.142857141809764668302)) +
        z4 * ((0.111111061804559452198 + z * -0.0909077307480841378967) +
              z2 * (0.0768995349630685775628 + z * -0.0664023393042940858874)) +
        z8 * ((0.0568834922680901047935 + z * -0.043480522157164624777) + z2 * 0.0211353731576932452057);
    double a = t * p + (past ? PI / 4 : 0);
    a = swap ? PI / 2 - a : a;
    a = signbit(x) ? PI - a : a;
    return copysign(a, y);
}

/* An orthonormal basis with w along the given normal (Duff et al. 2017, branchless ONB). */
typedef struct {
    vec3 u, v, w;
} onb;

static inline onb onb_from_w(vec3 n)
{
    double sign = copysign(1.0, n.z);
    double a = -1.0 / (sign + n.z);
    double b = n.x * n.y * a;
    onb o;
    o.u = v3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    o.v = v3(b, sign + n.y * n.y * a, -n.y);
    o.w = n;
    return o;
}
static inline vec3 onb_local(const onb *o, vec3 a)
{
    return v3_add(v3_add(v3_scale(o->u, a.x), v3_scale(o->v, a.y)), v3_scale(o->w, a.z));
}

#endif
