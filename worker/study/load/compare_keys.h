/* compare_keys: the job keys a compare job accepts where (top level, variant, sweep, reference),
   a key applied by name, and the short forms of keys in image names and labels. */
#ifndef COMPARE_KEYS_H
#define COMPARE_KEYS_H

#include <stddef.h>

#include "compare_model.h"
#include "scenefile/yamlx.h"

/* Why `key` may not be set where `where` says ("top", "variant", "sweep", "reference"), or NULL. */
const char *compare_keys_forbidden(const char *key, const char *where);

/* Check mapping n's keys: job keys (plus `extra`, may be NULL), none that `where` forbids. 0, or
   -1 with e at the key. */
int compare_keys_check(struct ydoc *d, yaml_node_t *n, const char *where, const char *extra, struct err *e);

/* job_apply of value v under the key named `key` (a scene under scenes:, a swept value): job_apply
   reads only the key's text, so a scalar node made here stands in for a key not in the file. */
int compare_keys_apply(struct job *j, struct ydoc *d, const char *key, yaml_node_t *v, struct err *e);

/* Append "-<short key><value>" to buf (n bytes), the value made file-name safe. */
void compare_keys_append(char *buf, size_t n, const char *key, const char *val);

#endif
