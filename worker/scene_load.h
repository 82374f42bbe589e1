/* scene_load: a scene YAML file (SPEC "Scene file") into a struct scene and a camera. */
#ifndef SCENE_LOAD_H
#define SCENE_LOAD_H

#include "camera.h"
#include "scene.h"

struct scene_file {
    struct scene *scene; /* owned */
    struct camera_desc camera;
    double aspect; /* camera aspect (width / height), default 1 */
};

/* Load path into out. 0, or -1 with e = "file:line:col: key: message"; nothing to free then. */
int scene_load(const char *path, struct scene_file *out, struct err *e);
void scene_file_free(struct scene_file *sf);

#endif
