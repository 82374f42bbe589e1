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

#endif
