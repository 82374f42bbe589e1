/* yamlx: libyaml documents with typed, position-reporting accessors for our strict loaders. */
#ifndef YAMLX_H
#define YAMLX_H

#include <stddef.h>
#include <stdint.h>
#include <yaml.h>

#include "base/err.h"
#include "base/vec3.h"

/* Largest YAML file we parse, and deepest nesting our loaders walk. */
#define YDOC_MAX_BYTES (8u << 20)
#define YDOC_MAX_DEPTH 32
#define YDOC_MAX_NODES 2000000
#define YDOC_MAX_VISITS 4000000
/* libyaml's composer looks each anchor and alias up in a list: bounded so that it stays quick. */
#define YDOC_MAX_ANCHORS 1000
#define YDOC_MAX_ALIASES 100000

struct ydoc {
    yaml_document_t doc;
    int loaded;
    char file[512];
    size_t *str_tagged; /* where the scalars tagged !!str start (mark index, ascending): libyaml's
                           document gives `!!str 16` the tag of a plain 16 */
    long n_str_tagged;
    double max_abs; /* > 0: yget_double refuses a number of larger magnitude (a scene: its floats) */
};

/* Read and parse path into d (one document). 0, or -1 with e at the problem's line:col.
   Free with ydoc_free, even after a failure. */
int ydoc_load(struct ydoc *d, const char *path, struct err *e);
void ydoc_free(struct ydoc *d);

/* ydoc_load of len bytes of YAML text at data (not kept), errors naming the file `name`; the
   caller bounds len. */
int ydoc_parse(struct ydoc *d, const char *name, const uint8_t *data, size_t len, struct err *e);

/* Expand YAML 1.1 merge keys in place (ydoc_load does it): each mapping's `<<: *a` or
   `<<: [*a, *b]` pairs are replaced by the entries of those mappings that it does not set itself
   (earlier sources first). 0, or -1 with e at a `<<` that names no mapping or loops. */
int ydoc_expand_merges(struct ydoc *d, struct err *e);
yaml_node_t *ydoc_root(struct ydoc *d);

/* Fill e at node n's position. Always -1. */
int ydoc_fail(struct ydoc *d, const yaml_node_t *n, struct err *e, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* Check that n is a mapping whose keys are scalars from `allowed` (NULL-terminated), with no
   duplicates; an unknown key gets a "did you mean" when one is close. `what` names the mapping
   in messages ("job", "camera"). */
int ymap_check(struct ydoc *d, yaml_node_t *n, const char *const *allowed, const char *what, struct err *e);

/* Whether n is a YAML null: a plain (unquoted) empty scalar, ~, null, Null or NULL, or one tagged
   !!null. An optional key given null takes its default: ymap_get and ymap_pair pass over it as if
   it were absent (ymap_check still sees its key). */
int ynull(const yaml_node_t *n);

/* The value node for key in mapping n (NULL when absent or null). */
yaml_node_t *ymap_get(struct ydoc *d, yaml_node_t *n, const char *key);

/* The value node for key in mapping n as written, null or not (NULL when absent). */
yaml_node_t *ymap_get_raw(struct ydoc *d, yaml_node_t *n, const char *key);

/* A required key is not there: "key: needs a value" at the value's position when it is written
   with a null value, else the message fmt at mapping n's. Always -1. */
int ymap_missing(struct ydoc *d, yaml_node_t *n, const char *key, struct err *e, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

/* Iterate: the i-th pair of mapping n (0-based) whose value is not null, or 0 when past the end. */
int ymap_pair(struct ydoc *d, yaml_node_t *n, int i, yaml_node_t **key, yaml_node_t **val);

/* The i-th item of sequence n, NULL past the end; ysize gives the count (-1 if not a sequence). */
yaml_node_t *yseq_item(struct ydoc *d, yaml_node_t *n, int i);
int yseq_len(yaml_node_t *n);

/* What node n is, for messages: "a mapping", "a list" or "a scalar". */
const char *ydoc_node_kind(const yaml_node_t *n);

/* Scalar text of n, or NULL if n is not a scalar. */
const char *yscalar(yaml_node_t *n);

/* Whether scalar n was written in quotes ("5", '5'): a string, never a number or a boolean. */
int yquoted(const yaml_node_t *n);

/* Whether scalar n was tagged !!str (`width: !!str 16`): a string, never a number or a boolean. */
int ystr_tagged(const struct ydoc *d, const yaml_node_t *n);

/* The note a !!str-tagged number's message ends with. */
#define YSTR_TAGGED_NOTE " (tagged !!str: a string, never a number)"

/* The note a quoted number's message ends with. */
#define YQUOTED_NOTE " (a quoted string: write numbers without quotes)"

/* The name near s (same letters in another case, or an edit or two away) among names (n of
   them, or NULL-terminated when n < 0), for a "did you mean"; NULL when none is. */
const char *ystr_nearest(const char *s, const char *const *names, int n);

#endif
