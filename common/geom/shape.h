/* shape: ray-primitive intersection, bounds, and the sampling of primitives lights use. */
#ifndef SHAPE_H
#define SHAPE_H

#include "sample/sampler.h"
#include "geom_types.h"

/* Fill p's derived fields from its geometry. scene_add_prim does it; call it again after
   editing a prim's geometry by hand. */
void shape_prepare(struct prim *p);

/* Fold p's rotate_y + translate into its world-space geometry where the shape allows: spheres,
   moving spheres, disks, cylinders, triangles, and rects turned by a multiple of 90 degrees
   (they stay axis-aligned). 1 and has_xform cleared when folded (the folded prim hits where the
   transformed one does, up to rounding); 0 and p unchanged for boxes, media, other rects, and
   spheres and rects when keep_uv (a texture reads their object-space uv). shape_bakes says
   which without changing p. */
int shape_bake(struct prim *p, int keep_uv);
int shape_bakes(const struct prim *p, int keep_uv);

/* Nearest hit of r with p in (t_min, t_max): 1 and h filled, else 0. Pure: a medium draws its
   free-flight distance from a hash of the ray, so the same ray always gets the same answer. */
int shape_hit(const struct prim *p, const ray *r, double t_min, double t_max, struct hit *h);

/* The ray's part of a medium's free-flight hash (shape_hit folds it in itself). */
uint64_t shape_ray_hash(const ray *r);

/* A medium's test in two steps: what the ray alone decides that bvh_hit starts while it
   traverses (|dir| and the free-flight uniform; ray_hash = shape_ray_hash(r)), then the hit in
   (t_min, t_max) as shape_hit gives it, which finds the boundary's crossings only when the
   flight could end inside. For media without a transform; bvh_hit starts the first step when
   it meets a medium and finishes once the nearest surface is known. */
void shape_medium_flight(const struct prim *p, const ray *r, uint64_t ray_hash, struct medium_flight *f);
int shape_medium_hit(const struct prim *p, const ray *r, const struct medium_flight *f, double t_min,
                     double t_max, struct hit *h);

/* Fill h->u, h->v for the primitive h->prim (only called when a texture needs them). */
void shape_uv(const struct prim *p, struct hit *h);

/* World-space bounds of p. */
void shape_bounds(const struct prim *p, vec3 *lo, vec3 *hi);

/* Area of p's surface (sphere, disk and rect, which lights use). */
double shape_area(const struct prim *p);

/* Whether light p draws its points from the job's light sampler (disk, rect); a sphere
   samples its cone of directions from the path's rng instead. */
int shape_light_uses_points(const struct prim *p);

/* The mean of light_pdf (shape_light_inline.h) over the scene's lights (the mixture's light side), taking
   known_pdf for light index known (-1: none); the scene has at least one light. */
double shape_lights_pdf(const struct scene *sc, vec3 o, vec3 dir, int known, double known_pdf);

#endif
