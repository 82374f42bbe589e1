/* box_point: the 27 points of a box that ray tests aim at, and a scene's box (test_bvh,
   test_packet). */
#ifndef BOX_POINT_H
#define BOX_POINT_H

#include <float.h>

#include "geom/scene.h"
#include "geom/shape.h"
#include "base/vec3.h"

/* k in [0, 27): every corner, edge midpoint, face centre and the centre of the box [lo, hi] */
static inline vec3 box_point(vec3 lo, vec3 hi, int k)
{
    int i = k % 3, j = k / 3 % 3, l = k / 9;
    double x = i == 0 ? lo.x : i == 1 ? hi.x : 0.5 * (lo.x + hi.x);
    double y = j == 0 ? lo.y : j == 1 ? hi.y : 0.5 * (lo.y + hi.y);
    double z = l == 0 ? lo.z : l == 1 ? hi.z : 0.5 * (lo.z + hi.z);
    return v3(x, y, z);
}

/* The box around every prim of sc into *lo, *hi. */
static inline void scene_box(const struct scene *sc, vec3 *lo, vec3 *hi)
{
    *lo = v3(DBL_MAX, DBL_MAX, DBL_MAX), *hi = v3(-DBL_MAX, -DBL_MAX, -DBL_MAX);
    for (int i = 0; i < sc->n_prims; i++) {
        vec3 l, h;
        shape_bounds(&sc->prims[i], &l, &h);
        *lo = v3_min(*lo, l), *hi = v3_max(*hi, h);
    }
}

#endif
