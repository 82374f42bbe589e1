/* scene_load: a scene YAML file into a struct scene and a camera. */
#ifndef SCENE_LOAD_H
#define SCENE_LOAD_H

#include <stdint.h>

#include "geom/camera.h"
#include "geom/scene.h"
#include "yamlx.h"

struct scene_file {
    struct scene *scene; /* owned */
    struct camera_desc camera;
    double aspect;     /* camera aspect (width / height), default 1 */
    char warning[600]; /* "" or one line: a light that lights nothing (scene_parse_facing_away) */
};

/* Every number in a scene lies within [-SCENE_MAX_ABS, SCENE_MAX_ABS], and every radius is at least
   SCENE_MIN_SIZE: the BVH's bounds and the framebuffer are floats (max 3.4e38), and a radius
   whose square underflows gives a light of no area. Beyond them a 1e200 triangle was called
   degenerate and a far camera's vup parallel (the products overflowed), and emit: [1e39, ...] or
   a 1e-300 radius rendered inf or nothing. */
#define SCENE_MAX_ABS 1e30
#define SCENE_MIN_SIZE 1e-30

/* A scene file read once (scene_src_read): its YAML parsed and kept until scene_src_free. */
struct scene_src {
    struct ydoc doc; /* doc.file: the scene file's path */
    int parsed;      /* 0: the YAML did not parse, parse_err says why (scene_load_src reports it) */
    struct err parse_err;
};

/* Read the scene file at path once: fold into *h what a render of it reads (the file's bytes,
   then the bytes of each image texture it names, so a changed texture makes outputs stale) and
   parse it into src. 0, or -1 with e when the file cannot be read; a scene that does not parse,
   or a texture that cannot be read, adds nothing to *h (scene_load_src reports those). Free src
   with scene_src_free either way. */
int scene_src_read(const char *path, struct scene_src *src, uint64_t *h, struct err *e);
void scene_src_free(struct scene_src *src);

/* Build the scene read into src (not changed: it may be loaded again) into out. 0, or -1 with
   e = "file:line:col: key: message"; nothing to free then. */
int scene_load_src(const struct scene_src *src, struct scene_file *out, struct err *e);

/* scene_src_read, scene_load_src and scene_src_free at once. */
int scene_load(const char *path, struct scene_file *out, struct err *e);
void scene_file_free(struct scene_file *sf);

/* scene_src_read's hash alone (the parse dropped). */
int scene_hash_inputs(const char *path, uint64_t *h, struct err *e);

#endif
