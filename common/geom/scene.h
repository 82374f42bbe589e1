/* scene: what a render draws — textures, materials, primitives, lights, BVH — in flat arrays. */
#ifndef SCENE_H
#define SCENE_H

#include "base/err.h"
#include "geom_types.h"

/* An empty scene; NULL on no memory. Free with scene_free (NULL is fine). */
struct scene *scene_new(void);
void scene_free(struct scene *sc);

/* Append one item; returns its index, or -1 on no memory. */
int scene_add_texture(struct scene *sc, const struct texture *t);
int scene_add_material(struct scene *sc, const struct material *m);
int scene_add_prim(struct scene *sc, const struct prim *p);
int scene_add_light(struct scene *sc, int prim);

/* Append a decoded image, taking ownership of its pixels (img is zeroed); its index or -1. */
int scene_add_image(struct scene *sc, struct rgb8 *img);

/* Make sure sc->perlin exists (one fixed-seed table shared by all noise textures). 0 or -1. */
int scene_use_perlin(struct scene *sc);

/* Whether prim p's material (an index into sc's materials) reads surface coordinates: an image
   texture. p need not be in sc yet. */
int scene_prim_needs_uv(const struct scene *sc, const struct prim *p);

/* Build the BVH once every prim is in. 0, or -1 with e filled. */
int scene_finish(struct scene *sc, struct err *e);

#endif
