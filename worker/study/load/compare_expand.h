/* compare_expand: a loaded compare job's reference and its combinations as ordinary jobs, from
   the loader's state (struct compare_loading, compare_load.c's while it reads one file). Internal. */
#ifndef COMPARE_EXPAND_H
#define COMPARE_EXPAND_H

#include "compare_model.h"
#include "scenefile/yamlx.h"

/* What the loader holds while it reads one file. */
struct compare_loading {
    struct ydoc d;
    struct compare *c;
    struct job base;                                  /* the top-level keys */
    struct job *scene_base;                           /* base + scene, per scene */
    yaml_node_t *variants, *sweep, *reference, *mask; /* mask: the top level's, every scene's */
    struct err *e;
};

/* The `reference:` key into each scene (settings, an image, or none). 0 or -1 with L->e. */
int compare_expand_reference(struct compare_loading *L);

/* Every combination (scene x variant x sweep point x seed) as a finished job. 0 or -1 with L->e. */
int compare_expand_items(struct compare_loading *L, yaml_node_t *root);

#endif
