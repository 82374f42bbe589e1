/* render_wide: a one-node scene's camera paths eight at a time with their whole state in float
   SIMD lanes (SPMD style): the nearest hit, the materials' scattering, the light mixture and the
   random draws, lane by lane under masks; a lane whose path ends takes the pixel's next sample.
   Internal to common/. */
#ifndef RENDER_WIDE_H
#define RENDER_WIDE_H

#include <stddef.h>
#include <stdint.h>

#include "rng.h"
#include "scene.h"

struct render_ctx;

/* The kernel is built by GCC for x86-64 (its AVX2 and FMA code through #pragma GCC target); with
   another compiler or CPU family wide_usable is 0 and the rest is never called. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define WIDE_KERNEL 1
#else
#define WIDE_KERNEL 0
#endif

/* The most lights a scene the wide kernel renders has. */
#define WIDE_MAX_LIGHTS 4
/* The most prims. */
#define WIDE_MAX_PRIMS 15

/* The scene's prims, materials and lights in the lanes' tables. */
struct wide_scene;

/* Whether the wide kernel renders sc: one BVH node; prims untransformed rects and spheres and
   boxes (at most WIDE_MAX_PRIMS); materials lambertian without texture, dielectric, light; lights
   rects and spheres, sampled (light_sampling_off: 0); albedos at most 1 and emission and
   background at most 2^64 (float lanes); a CPU with AVX2 and FMA. */
int wide_usable(const struct scene *sc, int light_sampling_off);

/* The tables for sc (wide_usable), valid while sc is; NULL on no memory. Free with
   wide_scene_free (NULL is fine). */
struct wide_scene *wide_scene_new(const struct scene *sc);
void wide_scene_free(struct wide_scene *ws);

/* The lanes of the wide kernel (float). */
#define WIDE_LANES 8

/* The nearest hit of each of eight rays (o, d by component: o[j * WIDE_LANES + i] is component j of
   ray i; rounded to float) for t in (t_min, FLT_MAX): its t, the prim's index in sc (-1: none) and
   the outward normal (n as o). For the tests. */
void wide_scene_hit(const struct wide_scene *ws, const double *o, const double *d, double t_min, double *t,
                    int *prim, double *n);

/* render_pixel's n samples of pixel (x, y) eight paths at a time in the lanes (ctx's wide
   scene), each sample's rng from the pixel's path stream *base as render_pixel_packet's;
   last: max_depth - 1. Sums as render_pixel_packet. */
void render_pixel_wide(struct render_ctx *ctx, int x, int y, size_t n, const struct rng *base, int last,
                       double sum[3], size_t *kept, uint64_t *nonfinite, uint64_t *rays);

#endif
