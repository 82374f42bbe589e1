/* wide_math: four double lanes (GCC vector extensions; AVX2 in the callers' avx2 clones) and what
   the wide path tracer (render_wide.c) does in them: lane picks, square roots, PCG32 streams one
   per lane, sin and cos of a turn, an orthonormal basis. Internal to common/. */
#ifndef WIDE_MATH_H
#define WIDE_MATH_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "rng.h"
#include "vec3.h"

/* Everything after this in the including file is compiled for AVX2: its callers run it only
   where the CPU has it (wide_usable). */
#pragma GCC target("avx2,fma")
#pragma GCC optimize("fp-contract=fast")
#include <immintrin.h>

typedef double d4 __attribute__((vector_size(32)));
typedef int64_t i4 __attribute__((vector_size(32)));
typedef uint64_t u4 __attribute__((vector_size(32)));

#define WAI inline __attribute__((always_inline))
#define WIDE_LANES 4

static WAI d4 d4s(double x)
{
    return (d4){x, x, x, x};
}

/* m ? a : b lane by lane (m all ones or all zeros per lane) */
static WAI d4 pick(i4 m, d4 a, d4 b)
{
    return _mm256_blendv_pd(b, a, (__m256d)m);
}

static WAI d4 d4_abs(d4 x)
{
    return (d4)((i4)x & ~(i4)d4s(-0.0));
}

static WAI d4 d4_min(d4 a, d4 b)
{
    return pick(a < b, a, b);
}

static WAI d4 wsqrt(d4 x)
{
    return _mm256_sqrt_pd(x);
}

/* one bit per lane whose mask is set */
static WAI int lane_bits(i4 m)
{
    return _mm256_movemask_pd((__m256d)m);
}

static WAI i4 lane_mask(int bits)
{
    return ((i4){bits, bits, bits, bits} & (i4){1, 2, 4, 8}) != 0;
}

/* PCG32 (rng.h) in each lane, one state per lane and a shared increment: the lanes' next outputs
   (below 2^32) and their states stepped. */
static WAI u4 rng4_u32(u4 *state, uint64_t inc)
{
    const u4 old = *state;
    *state = old * RNG_MULT + inc;
    const u4 x = (((old >> 18) ^ old) >> 27) & 0xffffffffu, rot = old >> 59;
    return ((x >> rot) | (x << ((32 - rot) & 31))) & 0xffffffffu;
}

/* x (below 2^32 per lane) / 2^32 as doubles: the integer's bits under 2^52's exponent, minus 2^52
   (exact; no 64-bit integer conversion in AVX2). */
static WAI d4 u32_unit(u4 x)
{
    return ((d4)(x | 0x4330000000000000ULL) - 0x1p52) * 0x1p-32;
}

/* v3_sincos_turn in the lanes (u in [0, 1)): the same series; the quadrant from comparisons. */
static WAI void sincos4(d4 u, d4 *s, d4 *c)
{
    const d4 x4 = 4 * u;
    const i4 q1 = x4 >= 1, q2 = x4 >= 2, q3 = x4 >= 3;
    const d4 q = (d4)((i4)d4s(1) & q1) + (d4)((i4)d4s(1) & q2) + (d4)((i4)d4s(1) & q3);
    const d4 x = (x4 - q - 0.5) * (PI / 2), y = x * x, y2 = y * y, y4 = y2 * y2;
    const d4 sn = x * ((1 + y * (-1.0 / 6)) + y2 * (1.0 / 120 + y * (-1.0 / 5040)) +
                       y4 * ((1.0 / 362880 + y * (-1.0 / 39916800)) +
                             y2 * (1.0 / 6227020800 + y * (-1.0 / 1307674368000))));
    const d4 cs =
        (1 + y * (-1.0 / 2)) + y2 * (1.0 / 24 + y * (-1.0 / 720)) +
        y4 * ((1.0 / 40320 + y * (-1.0 / 3628800)) + y2 * (1.0 / 479001600 + y * (-1.0 / 87178291200))) +
        y4 * y4 * (1.0 / 20922789888000);
    const double half_sqrt2 = 0.70710678118654752440;
    const d4 s0 = (sn + cs) * half_sqrt2, c0 = (cs - sn) * half_sqrt2;
    const i4 odd = q1 ^ q2 ^ q3, neg = (i4)d4s(-0.0) & q2;
    const d4 s1 = pick(odd, c0, s0), c1 = pick(odd, -s0, c0);
    *s = (d4)((i4)s1 ^ neg);
    *c = (d4)((i4)c1 ^ neg);
}

/* a.x u + a.y v + a.z w for onb_from_w(w) (Duff et al. 2017), lane by lane. */
static WAI void onb4_local(const d4 w[3], d4 ax, d4 ay, d4 az, d4 out[3])
{
    const d4 sign = (d4)(((i4)w[2] & (i4)d4s(-0.0)) | (i4)d4s(1.0));
    const d4 a = -1.0 / (sign + w[2]);
    const d4 b = w[0] * w[1] * a;
    const d4 ux = 1.0 + sign * w[0] * w[0] * a, uy = sign * b, uz = -sign * w[0];
    const d4 vx = b, vy = sign + w[1] * w[1] * a, vz = -w[1];
    out[0] = ux * ax + vx * ay + w[0] * az;
    out[1] = uy * ax + vy * ay + w[1] * az;
    out[2] = uz * ax + vz * ay + w[2] * az;
}

static WAI d4 dot4(const d4 a[3], const d4 b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The 32-byte rows at byte offset off of four structs (32-byte aligned there), as four columns. */
static WAI void transpose4(const void *const p[WIDE_LANES], size_t off, d4 c[4])
{
    d4 a0, a1, a2, a3;
    memcpy(&a0, (const char *)p[0] + off, sizeof a0);
    memcpy(&a1, (const char *)p[1] + off, sizeof a1);
    memcpy(&a2, (const char *)p[2] + off, sizeof a2);
    memcpy(&a3, (const char *)p[3] + off, sizeof a3);
    const d4 lo01 = __builtin_shufflevector(a0, a1, 0, 4, 2, 6), hi01 = __builtin_shufflevector(a0, a1, 1, 5, 3, 7);
    const d4 lo23 = __builtin_shufflevector(a2, a3, 0, 4, 2, 6), hi23 = __builtin_shufflevector(a2, a3, 1, 5, 3, 7);
    c[0] = __builtin_shufflevector(lo01, lo23, 0, 1, 4, 5);
    c[1] = __builtin_shufflevector(hi01, hi23, 0, 1, 4, 5);
    c[2] = __builtin_shufflevector(lo01, lo23, 2, 3, 6, 7);
    c[3] = __builtin_shufflevector(hi01, hi23, 2, 3, 6, 7);
}

#endif
