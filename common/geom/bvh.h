/* bvh: a binned-SAH bounding volume hierarchy of 8- or 16-wide nodes in one flat array, traversed
   without recursion. */
#ifndef BVH_H
#define BVH_H

#include "base/err.h"
#include "geom_types.h"
#include "shape.h"

/* The deepest a built tree gets (bvh_build.c); the traversal's stack is sized by it. */
#define BVH_DEPTH 96

/* How the traversal tests prim p in a leaf: BVH_LEAF_RECT, _SPHERE or _MEDIUM when it is one such
   without a transform, else BVH_LEAF_SHAPE (through shape_hit). */
static inline int bvh_prim_kind(const struct prim *p)
{
    if (p->has_xform)
        return BVH_LEAF_SHAPE;
    return p->type == PRIM_RECT     ? BVH_LEAF_RECT
           : p->type == PRIM_SPHERE ? BVH_LEAF_SPHERE
           : p->type == PRIM_MEDIUM ? BVH_LEAF_MEDIUM
                                    : BVH_LEAF_SHAPE;
}

/* Build sc->nodes and sc->prim_order over sc->prims. 0, or -1 with e filled (no memory). */
int bvh_build(struct scene *sc, struct err *e);

/* bvh_hit for a tree of several nodes, and for a scene of one node (at most BVH_WIDTH prims),
   each with its own frame: the one-node traversal needs no stack. */
int bvh_hit_tree(const struct scene *sc, const ray *r, double t_min, double t_max, struct hit *h);
int bvh_hit_node(const struct scene *sc, const ray *r, double t_min, double t_max, struct hit *h);

/* Nearest hit in (t_min, t_max) over the whole scene: 1 with h filled, else 0. */
static inline int bvh_hit(const struct scene *sc, const ray *r, double t_min, double t_max, struct hit *h)
{
    if (sc->n_nodes > 1)
        return bvh_hit_tree(sc, r, t_min, t_max, h);
    return sc->n_nodes == 1 && bvh_hit_node(sc, r, t_min, t_max, h);
}

#endif
