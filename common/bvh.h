/* bvh: a binned-SAH bounding volume hierarchy of 8- or 16-wide nodes in one flat array, traversed
   without recursion. */
#ifndef BVH_H
#define BVH_H

#include "scene.h"
#include "shape.h"

/* The deepest a built tree gets (bvh_build.c); the traversal's stack is sized by it. */
#define BVH_DEPTH 96

/* Build sc->nodes and sc->prim_order over sc->prims. 0, or -1 with e filled (no memory). */
int bvh_build(struct scene *sc, struct err *e);

/* Nearest hit in (t_min, t_max) over the whole scene: 1 with h filled, else 0. */
int bvh_hit(const struct scene *sc, const ray *r, double t_min, double t_max, struct hit *h);

#endif
