/* scene_loader: state shared by the scene loader's parts (sections, objects). Internal. */
#ifndef SCENE_LOADER_H
#define SCENE_LOADER_H

#include "geom/camera.h"
#include "geom/scene.h"
#include "yamlx.h"

/* Names given to textures and materials in the file, for lookups by name. */
struct names {
    const char *name[256];
    int n;
};

/* Limits on an image texture: bytes on disk and decoded pixels. */
#define TEXTURE_MAX_BYTES (64 << 20)
#define TEXTURE_MAX_PIXELS (4096L * 4096L)

struct loader {
    struct ydoc d;
    struct scene *sc;
    struct names tex, mat;
    struct err *e;
    const struct camera_desc *cam; /* loaded before the objects (a moving sphere's shutter) */
};

/* Index of s in nm, or -1. */
int loader_find_name(const struct names *nm, const char *s);

/* Fail at v with "<what> \"s\"" and a "did you mean" among names (NULL-terminated) when one is
   near, else the expected list. Always -1. */
int loader_unknown(struct loader *L, yaml_node_t *v, const char *what, const char *s,
                   const char *const *names, const char *expected);

/* Fail at v: key names s, which is not in nm (the section's names), with a "did you mean". -1. */
int loader_no_name(struct loader *L, yaml_node_t *v, const char *key, const char *s, const struct names *nm,
                   const char *section);

/* Read a colour (three numbers >= 0). */
int loader_color(struct loader *L, yaml_node_t *v, const char *key, vec3 *out);

/* Load the `objects:` list (root is the scene mapping, for a missing-list message). */
int load_objects(struct loader *L, yaml_node_t *list, yaml_node_t *root);

#endif
