/* compare_mask: a compare job's `mask:` (per scene: a rectangle or a white-on-black image), read
   and checked against the scene's size before anything renders. */
#ifndef COMPARE_MASK_H
#define COMPARE_MASK_H

#include "compare_model.h"
#include "scenefile/yamlx.h"

/* A scenes: list's item: a scene name (*scene = item, *mask NULL) or a mapping { scene: NAME,
   mask: {...} } (*scene its scene's value, *mask its mask's or NULL). 0, or -1 with e at the item. */
int compare_mask_item(struct ydoc *d, yaml_node_t *item, yaml_node_t **scene, yaml_node_t **mask,
                      struct err *e);

/* The mask node m ({ rect: [x0, y0, x1, y1] } or { image: FILE }, FILE relative to the job file
   job_path) into cs->mask, for cs's width and height. 0, or -1 with e at the key's line:col. */
int compare_mask_load(struct ydoc *d, yaml_node_t *m, const char *job_path, struct compare_scene *cs,
                      struct err *e);

#endif
