/* packet: the nearest hits of four rays at once in a scene of one BVH node, every prim tested
   exactly for all four rays in SIMD lanes (double), without the slab tests. */
#ifndef PACKET_H
#define PACKET_H

#include "scene.h"
#include "shape.h"

#define PACKET_LANES 4

/* The scene's prims in the one-node traversal's test order, with what the packet tests need. */
struct packet_scene;

/* The four lanes' hit records, each as bvh_hit fills it (u and v 0: shape_uv fills them when a
   texture reads them), so that a lane's record is used where it is, without a copy. */
struct packet_hits {
    struct hit h[PACKET_LANES];
};

/* Whether the packet pays in sc: one node, and every prim one packet_hit tests in its lanes (a
   box; a rect, sphere, disk or triangle without a transform). Any other prim but a medium
   would be tested lane by lane by shape_hit (right, but slower than bvh_hit). */
int packet_usable(const struct scene *sc);

/* The packet tests' table for sc, a scene of one node without media (packet_usable's, or
   others), valid while sc is; NULL on no memory. Free with packet_scene_free (NULL is fine). */
struct packet_scene *packet_scene_new(const struct scene *sc);
void packet_scene_free(struct packet_scene *ps);

/* bvh_hit(sc, r[i], t_min, t_max, &h_i) for the four lanes at once (every r[i] a ray; a lane
   whose result is not wanted may hold any ray): the same t and prim bit for bit, and the same
   hit record (packet_hit_of). Returns one bit per lane hit; ph holds the records of those. */
int packet_hit(const struct packet_scene *ps, const ray *const r[PACKET_LANES], double t_min, double t_max,
               struct packet_hits *ph);

#endif
