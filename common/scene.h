/* scene: what a render draws — textures, materials, primitives, lights, BVH — in flat arrays. */
#ifndef SCENE_H
#define SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"
#include "vec3.h"

enum tex_type { TEX_CHECKER };

struct texture {
    int type;
    vec3 odd, even; /* checker */
    double scale;   /* checker frequency */
};

enum mat_type { MAT_LAMBERTIAN, MAT_METAL, MAT_DIELECTRIC, MAT_LIGHT };

struct material {
    int type;
    vec3 albedo;  /* lambertian (when texture < 0), metal */
    int texture;  /* index into scene textures, or -1 */
    double fuzz;  /* metal */
    double ior;   /* dielectric */
    vec3 emit;    /* light */
};

enum prim_type { PRIM_SPHERE, PRIM_RECT, PRIM_DISK };

/* One primitive. Geometry is in object space; rotate_y (degrees) then translate place it. */
struct prim {
    int type;
    int material;
    int flip;      /* rect: face the negative axis instead */
    int has_xform; /* cos_y/sin_y/offset valid */
    double cos_y, sin_y;
    vec3 offset;
    union {
        struct {
            vec3 center;
            double radius;
        } sphere;
        struct {
            int axis;         /* normal axis: 0 = x (plane yz), 1 = y (xz), 2 = z (xy) */
            double a0, a1;    /* extent along the first in-plane axis */
            double b0, b1;    /* extent along the second in-plane axis */
            double k;         /* the plane's coordinate on the normal axis */
        } rect;
        struct {
            vec3 center, normal, e1, e2; /* unit normal (front), frame e1 x e2 = normal */
            double radius;
        } disk;
    } g;
};

struct bvh_node {
    float lo[3], hi[3];
    int32_t start; /* leaf: first index into prim_order; interior: right child */
    int32_t count; /* leaf: number of prims; interior: 0 (left child is the next node) */
};

struct scene {
    struct texture *textures;
    int n_textures;
    struct material *materials;
    int n_materials;
    struct prim *prims;
    int n_prims;
    int *lights; /* prims importance-sampled by the light pdf */
    int n_lights;
    vec3 background;
    /* built by scene_finish */
    struct bvh_node *nodes;
    int n_nodes;
    int32_t *prim_order;
};

/* An empty scene; NULL on no memory. Free with scene_free (NULL is fine). */
struct scene *scene_new(void);
void scene_free(struct scene *sc);

/* Append one item; returns its index, or -1 on no memory. */
int scene_add_texture(struct scene *sc, const struct texture *t);
int scene_add_material(struct scene *sc, const struct material *m);
int scene_add_prim(struct scene *sc, const struct prim *p);
int scene_add_light(struct scene *sc, int prim);

/* Build the BVH once every prim is in. 0, or -1 with e filled. */
int scene_finish(struct scene *sc, struct err *e);

#endif
