/* geom_types: the geometry's data, types only: a scene's textures, materials, primitives and BVH
   nodes (scene.h builds them), a ray's hit and a medium's free flight (shape.h). Every geom
   header that needs the data includes this one, not the module that builds or tests it. */
#ifndef GEOM_TYPES_H
#define GEOM_TYPES_H

#include <stddef.h>
#include <stdint.h>

#include "base/vec3.h"
#include "image/image.h"
#include "perlin.h"

enum tex_type { TEX_CHECKER, TEX_NOISE, TEX_IMAGE };

struct texture {
    int type;
    vec3 odd, even; /* checker */
    double scale;   /* checker: frequency; noise: frequency of the marble bands */
    int image;      /* image: index into the scene's images */
};

/* isotropic: the phase function of a constant medium (albedo or texture, like lambertian). */
enum mat_type { MAT_LAMBERTIAN, MAT_METAL, MAT_DIELECTRIC, MAT_LIGHT, MAT_ISOTROPIC };

struct material {
    int type;
    vec3 albedo; /* lambertian (when texture < 0), metal */
    int texture; /* index into scene textures, or -1 */
    double fuzz; /* metal */
    double ior;  /* dielectric */
    vec3 emit;   /* light */
};

enum prim_type {
    PRIM_SPHERE,
    PRIM_RECT,
    PRIM_DISK,
    PRIM_MOVING_SPHERE,
    PRIM_BOX,
    PRIM_CYLINDER,
    PRIM_TRIANGLE,
    PRIM_MEDIUM
};

/* One primitive. Geometry is in object space; rotate_y (degrees) then translate place it.
   scene_finish folds the transform into the geometry of the shapes it maps onto themselves
   (shape_bake) and clears has_xform; boxes, media, rects turned by other than quarter turns,
   and textured spheres and rects keep it.
   Fields marked "derived" are filled from the others by shape_prepare (scene_add_prim calls it). */
struct prim {
    int type;
    int material;
    int flip;      /* rect: face the negative axis instead */
    int has_xform; /* cos_y/sin_y/offset valid */
    double cos_y, sin_y;
    vec3 offset;
    double area; /* derived: the surface area of a sphere, rect or disk (light pdfs) */
    union {
        struct {
            vec3 center;
            double radius;
        } sphere;
        struct {
            int axis;        /* normal axis: 0 = x (plane yz), 1 = y (xz), 2 = z (xy) */
            double a0, a1;   /* extent along the first in-plane axis */
            double b0, b1;   /* extent along the second in-plane axis */
            double k;        /* the plane's coordinate on the normal axis */
            vec3 n, ea, eb;  /* derived: unit vectors along the normal axis and the in-plane axes */
            long on, oa, ob; /* derived: byte offsets of those axes' components in a vec3 */
            vec3 ball_c;     /* derived: centre of the ball through the corners (light pdf's cone test) */
            double ball_r2, ball_r2_out; /* derived: its radius^2 (1 + 1e-9), and that (1 + 1e-6) */
        } rect;
        struct {
            vec3 center, normal, e1, e2; /* unit normal (front), frame e1 x e2 = normal */
            double radius;
            double r2, r2_out; /* derived: radius^2, and radius^2 (1 + 1e-6) (light pdf's cone test) */
        } disk;
        struct {
            vec3 center0, velocity; /* center at time t: center0 + t * velocity */
            double radius;
            double time_lo, time_hi; /* the shutter interval its bounds cover */
        } msphere;
        struct {
            vec3 lo, hi;
        } box;
        struct {
            vec3 base, axis; /* unit axis from base to top */
            double height, radius;
        } cyl;
        struct {
            vec3 v0, e1, e2, normal; /* vertices v0, v0 + e1, v0 + e2; unit normal e1 x e2 */
        } tri;
        struct {
            vec3 center; /* boundary sphere */
            double radius;
            double neg_inv_density;
            uint64_t hash_key;   /* derived: the medium's part of the free-flight hash */
            double mean_free_lo; /* derived: -neg_inv_density (1 - 1e-9), flight bounds' margin in */
        } medium;
    } g;
};

/* A wide BVH node: the boxes of up to BVH_WIDTH children, stored axis by axis so SIMD
   operations test four at a time (bvh.c). Boxes are floats rounded outward. A scene of at most
   BVH_WIDTH leaves is one node; larger scenes use nodes of BVH_WIDTH / 2 (bvh_build.c). */
#define BVH_WIDTH 16
/* A leaf lane's kind (bvh_node.kind): one untransformed rect, sphere or medium, one other prim
   that shape_hit tests, or anything else. */
enum { BVH_LEAF_ANY, BVH_LEAF_RECT, BVH_LEAF_SPHERE, BVH_LEAF_SHAPE, BVH_LEAF_MEDIUM };
struct bvh_node {
    float lo[3][BVH_WIDTH], hi[3][BVH_WIDTH]; /* child c spans lo[axis][c] .. hi[axis][c]; unused: empty */
    int32_t child[BVH_WIDTH];  /* count 0: index of an interior node; a leaf of a kind: its prim's
                                  index; else (BVH_LEAF_ANY) its first prim_order index */
    uint16_t count[BVH_WIDTH]; /* prims in a leaf child; 0 for an interior child or an unused slot */
    uint16_t leaves;           /* bit c set: child c is a leaf */
    uint8_t quads;             /* groups of four lanes in use: the rest are empty */
    uint8_t kind[BVH_WIDTH];   /* leaf child c: BVH_LEAF_RECT etc. when it is one such prim, else 0 */
    uint8_t pad[13];           /* 512 bytes: nodes start on cache lines */
};

struct scene {
    struct texture *textures;
    int n_textures;
    struct material *materials;
    int n_materials;
    struct prim *prims;
    int n_prims;
    int *lights; /* prims importance-sampled by the light pdf (the mixture's: emitters and sample: true) */
    int n_lights;
    /* built by scene_finish: the lights whose material emits, next-event estimation's set: their
       prims and their indices in lights */
    int *emitters, *emitter_lights;
    int n_emitters;
    vec3 background;
    struct rgb8 *images; /* decoded image textures */
    int n_images;
    struct perlin *perlin; /* the noise textures' table, NULL when none */
    /* built by scene_finish */
    struct bvh_node *nodes;
    int n_nodes;
    int32_t *prim_order;
};

#define HIT_EPS 0.001

struct hit {
    double t;
    vec3 p;      /* world-space point */
    vec3 n;      /* unit normal facing against the ray */
    double u, v; /* surface coordinates, filled by shape_uv when a texture needs them */
    int front;   /* the ray hit the outward (front) side */
    int prim;
};

/* What a medium's test starts while the BVH traverses (shape_medium_flight): |dir| and the
   free-flight uniform. */
struct medium_flight {
    double len, u;
};

#endif
