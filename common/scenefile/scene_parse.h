/* scene_parse: the state and checks shared by the scene loader's parts (scene_load.c: camera,
   textures, materials; scene_objects.c: objects). Internal. */
#ifndef SCENE_PARSE_H
#define SCENE_PARSE_H

#include "geom/camera.h"
#include "geom/scene.h"
#include "yamlx.h"

/* Every number in a scene lies within [-SCENE_MAX_ABS, SCENE_MAX_ABS], and every radius is at least
   SCENE_MIN_SIZE: the BVH's bounds and the framebuffer are floats (max 3.4e38), and a radius
   whose square underflows gives a light of no area. Beyond them a 1e200 triangle was called
   degenerate and a far camera's vup parallel (the products overflowed), and emit: [1e39, ...] or
   a 1e-300 radius rendered inf or nothing. */
#define SCENE_MAX_ABS 1e30
#define SCENE_MIN_SIZE 1e-30

/* Names given to textures and materials in the file, for lookups by name. */
struct names {
    const char *name[256];
    int n;
};

/* Limits on an image texture: bytes on disk and decoded pixels. */
#define TEXTURE_MAX_BYTES (64 << 20)
#define TEXTURE_MAX_PIXELS (4096L * 4096L)
/* Limit on a scene's image textures together: their files' bytes as read, and their decoded
   pixels (3 bytes each; a file several textures name counts once). Each limit above held, but
   256 textures of one 4096x4096 file decoded 256 times took 12 GiB. */
#define TEXTURE_BUDGET_BYTES ((size_t)1 << 30)

struct scene_parse {
    struct ydoc d;
    const struct scene_src *src; /* the scene file as read: its image textures' bytes */
    struct scene *sc;
    struct names tex, mat;
    struct err *e;
    int *file_image;               /* per src->files entry: its decoded image in sc->images, -1 before */
    size_t texture_bytes;          /* the decoded images' pixels so far (TEXTURE_BUDGET_BYTES) */
    const struct camera_desc *cam; /* loaded before the objects (a moving sphere's shutter) */
    int (*light_pos)[2];           /* per sc->lights entry: its object's line, col (1-based) */
    int light_pos_cap;
};

/* After scene_finish (lights baked into world space): the first rect or disk light of L->sc whose
   front face sees neither the camera nor any part of a non-emitting object's bounds, so that it
   lights nothing, into buf as "file:line:col: the disk light (material \"lamp\") faces away ...";
   "" when there is none. */
void scene_parse_facing_away(const struct scene_parse *L, char *buf, size_t n);

/* Index of s in nm, or -1. */
int scene_parse_find_name(const struct names *nm, const char *s);

/* Fail at v with "<what> \"s\"" and a "did you mean" among names (NULL-terminated) when one is
   near, else the expected list. Always -1. */
int scene_parse_unknown(struct scene_parse *L, yaml_node_t *v, const char *what, const char *s,
                        const char *const *names, const char *expected);

/* Fail at v: key names s, which is not in nm (the section's names), with a "did you mean". -1. */
int scene_parse_no_name(struct scene_parse *L, yaml_node_t *v, const char *key, const char *s,
                        const struct names *nm, const char *section);

/* Read a colour (three numbers >= 0). */
int scene_parse_color(struct scene_parse *L, yaml_node_t *v, const char *key, vec3 *out);

#endif
