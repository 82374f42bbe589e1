/* scene_objects: a scene file's `objects:` list into the scene's prims. Internal to the loader. */
#ifndef SCENE_OBJECTS_H
#define SCENE_OBJECTS_H

#include "scene_parse.h"

/* Load the `objects:` list (root is the scene mapping, for a missing-list message). 0, or -1
   with L->e at the offending key. */
int scene_objects_load(struct scene_parse *L, yaml_node_t *list, yaml_node_t *root);

#endif
