/* scene_load: a scene YAML file into a struct scene and a camera. */
#ifndef SCENE_LOAD_H
#define SCENE_LOAD_H

#include <stdint.h>

#include "geom/camera.h"
#include "geom/scene.h"
#include "scene_src.h"
#include "yamlx.h"

struct scene_file {
    struct scene *scene; /* owned */
    struct camera_desc camera;
    double aspect;     /* camera aspect (width / height), default 1 */
    char warning[600]; /* "" or one line: a light that lights nothing (scene_parse_facing_away) */
};

/* Build the scene read into src (not changed: it may be loaded again) into out. 0, or -1 with
   e = "file:line:col: key: message"; nothing to free then. */
int scene_load_src(const struct scene_src *src, struct scene_file *out, struct err *e);

/* scene_src_read, scene_load_src and scene_src_free at once. */
int scene_load(const char *path, struct scene_file *out, struct err *e);
void scene_file_free(struct scene_file *sf);

#endif
