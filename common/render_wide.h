/* render_wide: a one-node scene's camera paths four at a time with their whole state in double
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

/* The most lights a scene the wide kernel renders has. */
#define WIDE_MAX_LIGHTS 4

/* The scene's prims, materials and lights in the lanes' tables. */
struct wide_scene;

/* Whether the wide kernel renders sc: one BVH node; prims untransformed rects and spheres and
   boxes; materials lambertian without texture, dielectric, light; lights rects and spheres,
   sampled (light_sampling_off: 0). */
int wide_usable(const struct scene *sc, int light_sampling_off);

/* The tables for sc (wide_usable), valid while sc is; NULL on no memory. Free with
   wide_scene_free (NULL is fine). */
struct wide_scene *wide_scene_new(const struct scene *sc);
void wide_scene_free(struct wide_scene *ws);

/* The nearest hit of each of four rays (o, d by component, lane i = ray i) for t in (t_min,
   inf): its t, the prim's index in sc (-1: none) and the outward normal. For the tests. */
void wide_scene_hit(const struct wide_scene *ws, const double o[3][4], const double d[3][4], double t_min,
                    double t[4], int prim[4], double n[3][4]);

/* render_pixel's n samples of pixel (x, y) four paths at a time in the lanes (ctx's wide
   scene), each sample's rng from the pixel's path stream *base as render_pixel_packet's;
   last: max_depth - 1. Sums as render_pixel_packet. */
void render_pixel_wide(struct render_ctx *ctx, int x, int y, size_t n, const struct rng *base, int last,
                       double sum[3], size_t *kept, uint64_t *nonfinite, uint64_t *rays);

#endif
