/* simd: which vector paths are compiled. They only speed up intersection and traversal and
   return the scalar code's answers bit for bit; WORKER_NO_SIMD=1 (make SIMD=0) builds the
   generic forms alone, which the determinism test renders against the default build. */
#ifndef SIMD_H
#define SIMD_H

#if defined(__SSE2__) && !defined(WORKER_NO_SIMD)
#define SIMD_SSE 1
#else
#define SIMD_SSE 0
#endif

#ifdef WORKER_NO_SIMD
#define SIMD_LANES 0 /* render_lanes.c hits each lane's ray by the scalar traversal, not packet_hit */
#else
#define SIMD_LANES 1
#endif

/* AVX2 paths chosen at run time (x86-64, GCC or clang, vector paths on): functions marked
   __attribute__((target("avx2"))), called only where simd_avx2() finds the processor has it, each
   returning its generic form's answers bit for bit. */
#if SIMD_SSE && defined(__x86_64__) && defined(__GNUC__)
#define SIMD_AVX2 1
#else
#define SIMD_AVX2 0
#endif

/* 1 when this processor runs the AVX2 paths, else 0 (always 0 without SIMD_AVX2). */
static inline int simd_avx2(void)
{
#if SIMD_AVX2
    return __builtin_cpu_supports("avx2") != 0;
#else
    return 0;
#endif
}

#endif
