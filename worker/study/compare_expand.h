/* compare_loading: what the compare job loader's parts share while reading one file. Internal. */
#ifndef COMPARE_EXPAND_H
#define COMPARE_EXPAND_H

#include "compare.h"
#include "scenefile/yamlx.h"

/* What the loader holds while it reads one file. */
struct loading {
    struct ydoc d;
    struct compare *c;
    struct job base;        /* the top-level keys */
    struct job *scene_base; /* base + scene, per scene */
    yaml_node_t *variants, *sweep, *reference;
    struct err *e;
};

/* job_apply of value v under the key named `key` (a scene under scenes:, a swept value). */
int compare_apply(struct job *j, struct ydoc *d, const char *key, yaml_node_t *v, struct err *e);

/* Check mapping n's keys: job keys (plus `extra`, may be NULL), none that `where` forbids
   ("top", "variant", "sweep", "reference"). 0, or -1 with L->e at the key. */
int compare_check_keys(struct loading *L, yaml_node_t *n, const char *where, const char *extra);

/* Append "-<short key><value>" to buf (n bytes), the value made file-name safe. */
void compare_add_part(char *buf, size_t n, const char *key, const char *val);

/* The `reference:` key into each scene (settings, an image, or none). 0 or -1. */
int compare_load_reference(struct loading *L);

/* Every combination (scene x variant x sweep point x seed) as a finished job. 0 or -1. */
int compare_expand(struct loading *L, yaml_node_t *root);

#endif
