/* scene: growing the scene's flat arrays while a loader fills them, and freeing them. */
#include "scene.h"

#include <stdlib.h>

#include "bvh.h"

struct scene *scene_new(void)
{
    struct scene *sc = calloc(1, sizeof *sc);
    return sc;
}

void scene_free(struct scene *sc)
{
    if (!sc)
        return;
    free(sc->textures);
    free(sc->materials);
    free(sc->prims);
    free(sc->lights);
    free(sc->nodes);
    free(sc->prim_order);
    for (int i = 0; i < sc->n_images; i++)
        rgb8_free(&sc->images[i]);
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
    unsigned char *dst = (unsigned char *)*arr + (size_t)*n * size;
    const unsigned char *src = item;
    for (size_t i = 0; i < size; i++)
        dst[i] = src[i];
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
    return push((void **)&sc->prims, &sc->n_prims, sizeof *p, p);
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

int scene_finish(struct scene *sc, struct err *e)
{
    return bvh_build(sc, e);
}
