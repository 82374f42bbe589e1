/* wide_math: eight float lanes (GCC vector extensions, AVX2) and what
   the wide path tracer (render_wide.c) does in them: lane picks, square roots, PCG32 streams one
   per lane, sin and cos of a turn, an orthonormal basis, table lookups. Internal to common/. */
#ifndef WIDE_MATH_H
#define WIDE_MATH_H

#include <math.h>
#include <stdint.h>

#include "rng.h"
#include "vec3.h"

/* Everything after this in the including file is compiled for AVX2 and FMA, and contracts a * b + c
   to fma: its callers run it only where the CPU has them (wide_usable). */
#pragma GCC target("avx2,fma")
#pragma GCC optimize("fp-contract=fast")
#include <immintrin.h>

typedef float f8 __attribute__((vector_size(32)));
typedef int32_t i8 __attribute__((vector_size(32)));
typedef uint32_t u8 __attribute__((vector_size(32)));
typedef uint64_t u4 __attribute__((vector_size(32)));

#define WAI inline __attribute__((always_inline))

static WAI f8 f8s(float x)
{
    return (f8){x, x, x, x, x, x, x, x};
}

static WAI i8 i8s(int32_t x)
{
    return (i8){x, x, x, x, x, x, x, x};
}

/* m ? a : b lane by lane (m all ones or all zeros per lane) */
static WAI f8 pick(i8 m, f8 a, f8 b)
{
    return _mm256_blendv_ps(b, a, (__m256)m);
}

static WAI i8 picki(i8 m, i8 a, i8 b)
{
    return (i8)_mm256_blendv_ps((__m256)b, (__m256)a, (__m256)m);
}

static WAI f8 f8_abs(f8 x)
{
    return (f8)((i8)x & i8s(0x7fffffff));
}

static WAI f8 f8_min(f8 a, f8 b)
{
    return _mm256_min_ps(a, b);
}

static WAI f8 f8_max(f8 a, f8 b)
{
    return _mm256_max_ps(a, b);
}

static WAI f8 wsqrt(f8 x)
{
    return _mm256_sqrt_ps(x);
}

/* one bit per lane whose mask is set */
static WAI int lane_bits(i8 m)
{
    return _mm256_movemask_ps((__m256)m);
}

static WAI i8 lane_mask(int bits)
{
    return (i8s(bits) & (i8){1, 2, 4, 8, 16, 32, 64, 128}) != 0;
}

/* PCG32 (rng.h), one 64-bit state per lane in two vectors of four (lanes 0-3, 4-7), a shared
   increment. */
struct rng8 {
    u4 lo, hi;
};

static WAI u4 rng4_u32(u4 *state, uint64_t inc)
{
    const u4 old = *state;
    *state = old * RNG_MULT + inc;
    const u4 x = (((old >> 18) ^ old) >> 27) & 0xffffffffu, rot = old >> 59;
    return ((x >> rot) | (x << ((32 - rot) & 31))) & 0xffffffffu;
}

/* the lanes' next outputs, their states stepped */
static WAI u8 rng8_u32(struct rng8 *r, uint64_t inc)
{
    const u8 a = (u8)rng4_u32(&r->lo, inc), b = (u8)rng4_u32(&r->hi, inc);
    return __builtin_shufflevector(a, b, 0, 2, 4, 6, 8, 10, 12, 14);
}

/* x's top 24 bits / 2^24: uniform in [0, 1), exact in a float */
static WAI f8 u32_unit(u8 x)
{
    return __builtin_convertvector((i8)(x >> 8), f8) * 0x1p-24f;
}

/* v3_sincos_turn in the lanes (u in [0, 1)): its series to float's precision; the quadrant from
   comparisons. */
static WAI void sincos8(f8 u, f8 *s, f8 *c)
{
    const f8 x4 = 4 * u;
    const i8 q1 = x4 >= 1, q2 = x4 >= 2, q3 = x4 >= 3;
    const f8 q = (f8)((i8)f8s(1) & q1) + (f8)((i8)f8s(1) & q2) + (f8)((i8)f8s(1) & q3);
    const f8 x = (x4 - q - 0.5f) * (float)(PI / 2), y = x * x, y2 = y * y;
    const f8 sn =
        x * ((1 + y * (-1.0f / 6)) + y2 * (1.0f / 120 + y * (-1.0f / 5040)) + y2 * y2 * (1.0f / 362880));
    const f8 cs = (1 + y * (-1.0f / 2)) + y2 * (1.0f / 24 + y * (-1.0f / 720)) +
                  y2 * y2 * (1.0f / 40320 + y * (-1.0f / 3628800));
    const float half_sqrt2 = 0.70710678118654752440f;
    const f8 s0 = (sn + cs) * half_sqrt2, c0 = (cs - sn) * half_sqrt2;
    const i8 odd = q1 ^ q2 ^ q3, neg = (i8)f8s(-0.0f) & q2;
    const f8 s1 = pick(odd, c0, s0), c1 = pick(odd, -s0, c0);
    *s = (f8)((i8)s1 ^ neg);
    *c = (f8)((i8)c1 ^ neg);
}

/* a.x u + a.y v + a.z w for onb_from_w(w) (Duff et al. 2017), lane by lane. */
static WAI void onb8_local(const f8 w[3], f8 ax, f8 ay, f8 az, f8 out[3])
{
    const f8 sign = (f8)(((i8)w[2] & (i8)f8s(-0.0f)) | (i8)f8s(1.0f));
    const f8 a = -1.0f / (sign + w[2]);
    const f8 b = w[0] * w[1] * a;
    const f8 ux = 1.0f + sign * w[0] * w[0] * a, uy = sign * b, uz = -sign * w[0];
    const f8 vx = b, vy = sign + w[1] * w[1] * a, vz = -w[1];
    out[0] = ux * ax + vx * ay + w[0] * az;
    out[1] = uy * ax + vy * ay + w[1] * az;
    out[2] = uz * ax + vz * ay + w[2] * az;
}

static WAI f8 dot8(const f8 a[3], const f8 b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Column c of a table of up to 16 entries (lo: 0-7, hi: 8-15) at each lane's index k. */
static WAI f8 lookup16(f8 lo, f8 hi, i8 k)
{
    return pick(k > 7, _mm256_permutevar8x32_ps(hi, (__m256i)k), _mm256_permutevar8x32_ps(lo, (__m256i)k));
}

#endif
