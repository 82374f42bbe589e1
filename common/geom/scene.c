/* scene: growing the scene's flat arrays while a loader fills them, and freeing them. */
#include "scene.h"

#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "shape.h"
#include "texture.h"

struct scene *scene_new(void)
{
    return calloc(1, sizeof(struct scene));
}

void scene_free(struct scene *sc)
{
    if (!sc)
        return;
    free(sc->textures);
    free(sc->materials);
    free(sc->prims);
    free(sc->lights);
    free(sc->emitters);
    free(sc->emitter_lights);
    free(sc->nodes);
    free(sc->prim_order);
    for (int i = 0; i < sc->n_images; i++)
        image_free(&sc->images[i]);
    free(sc->images);
    free(sc->perlin);
    free(sc);
}

/* Append one element of size `size` to *arr (holding *n), doubling at powers of two. */
static int push(void **arr, int *n, size_t size, const void *item)
{
    if (*n == 0 || (*n & (*n - 1)) == 0) {
        size_t cap = *n == 0 ? 4 : (size_t)*n * 2;
        void *grown = realloc(*arr, cap * size);
        if (!grown)
            return -1;
        *arr = grown;
    }
    memcpy((unsigned char *)*arr + (size_t)*n * size, item, size);
    return (*n)++;
}

int scene_add_texture(struct scene *sc, const struct texture *t)
{
    return push((void **)&sc->textures, &sc->n_textures, sizeof *t, t);
}

int scene_add_material(struct scene *sc, const struct material *m)
{
    return push((void **)&sc->materials, &sc->n_materials, sizeof *m, m);
}

int scene_add_prim(struct scene *sc, const struct prim *p)
{
    int i = push((void **)&sc->prims, &sc->n_prims, sizeof *p, p);
    if (i >= 0)
        shape_prepare(&sc->prims[i]);
    return i;
}

int scene_add_light(struct scene *sc, int prim)
{
    return push((void **)&sc->lights, &sc->n_lights, sizeof prim, &prim);
}

int scene_add_image(struct scene *sc, struct rgb8 *img)
{
    int i = push((void **)&sc->images, &sc->n_images, sizeof *img, img);
    if (i >= 0)
        *img = (struct rgb8){0};
    return i;
}

int scene_use_perlin(struct scene *sc)
{
    if (sc->perlin)
        return 0;
    if (!(sc->perlin = malloc(sizeof *sc->perlin)))
        return -1;
    perlin_init(sc->perlin, PERLIN_SEED);
    return 0;
}

int scene_prim_needs_uv(const struct scene *sc, const struct prim *p)
{
    if (p->material < 0 || p->material >= sc->n_materials)
        return 0;
    int t = sc->materials[p->material].texture;
    return t >= 0 && t < sc->n_textures && texture_needs_uv(&sc->textures[t]);
}

int scene_finish(struct scene *sc, struct err *e)
{
    /* transforms folded into world-space geometry where exact: such prims take the inline
       sphere test and shape_hit's direct path */
    for (int i = 0; i < sc->n_prims; i++) {
        struct prim *p = &sc->prims[i];
        if (!shape_bake(p, scene_prim_needs_uv(sc, p)))
            shape_prepare(p);
    }
    /* lights are sampled in world space: the loader admits only transforms that fold */
    for (int i = 0; i < sc->n_lights; i++)
        if (sc->prims[sc->lights[i]].has_xform)
            return err_set(e, NULL, 0, 0, "internal: light %d keeps a transform shape_bake cannot fold", i);
    free(sc->emitters);
    free(sc->emitter_lights);
    sc->emitters = malloc(((size_t)sc->n_lights + 1) * sizeof *sc->emitters);
    sc->emitter_lights = malloc(((size_t)sc->n_lights + 1) * sizeof *sc->emitter_lights);
    sc->n_emitters = 0;
    if (!sc->emitters || !sc->emitter_lights)
        return err_set(e, NULL, 0, 0, "out of memory for the scene's list of emitters");
    for (int i = 0; i < sc->n_lights; i++) {
        const int m = sc->prims[sc->lights[i]].material;
        if (m >= 0 && m < sc->n_materials && sc->materials[m].type == MAT_LIGHT) {
            sc->emitters[sc->n_emitters] = sc->lights[i];
            sc->emitter_lights[sc->n_emitters++] = i;
        }
    }
    return bvh_build(sc, e);
}
