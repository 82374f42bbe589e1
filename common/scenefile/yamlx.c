/* yamlx: reading a loaded YAML document (yamlx_load.c) with file:line:col errors. */
#include "yamlx.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

int ystr_tagged(const struct ydoc *d, const yaml_node_t *n)
{
    if (!n || n->type != YAML_SCALAR_NODE)
        return 0;
    long lo = 0, hi = d->n_str_tagged;
    while (lo < hi) {
        long mid = lo + (hi - lo) / 2;
        if (d->str_tagged[mid] < n->start_mark.index)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < d->n_str_tagged && d->str_tagged[lo] == n->start_mark.index;
}

yaml_node_t *ydoc_root(struct ydoc *d)
{
    return d->loaded ? yaml_document_get_root_node(&d->doc) : NULL;
}

int ydoc_fail(struct ydoc *d, const yaml_node_t *n, struct err *e, const char *fmt, ...)
{
    char msg[sizeof e->msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    int line = n ? (int)n->start_mark.line + 1 : 0, col = n ? (int)n->start_mark.column + 1 : 0;
    return err_set(e, d->file, line, col, "%s", msg);
}

const char *yscalar(yaml_node_t *n)
{
    return n && n->type == YAML_SCALAR_NODE ? (const char *)n->data.scalar.value : NULL;
}

/* Edit distance of two short strings (for "did you mean"). */
static int ystr_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 63 || lb > 63)
        return 99;
    int row[64];
    for (size_t j = 0; j <= lb; j++)
        row[j] = (int)j;
    for (size_t i = 1; i <= la; i++) {
        int prev = row[0];
        row[0] = (int)i;
        for (size_t j = 1; j <= lb; j++) {
            int cur = row[j];
            int best = prev + (a[i - 1] != b[j - 1]);
            if (row[j] + 1 < best)
                best = row[j] + 1;
            if (row[j - 1] + 1 < best)
                best = row[j - 1] + 1;
            row[j] = best;
            prev = cur;
        }
    }
    return row[lb];
}

const char *ystr_nearest(const char *s, const char *const *names, int n)
{
    const char *near = NULL;
    int best = 3;
    for (int i = 0; n < 0 ? names[i] != NULL : i < n; i++) {
        /* the same letters in another case (WIDTH, Max_Depth) are as near as can be */
        int dist = strcasecmp(s, names[i]) == 0 ? 0 : ystr_distance(s, names[i]);
        if (dist < best && dist <= (int)strlen(names[i]) / 2) {
            best = dist;
            near = names[i];
        }
    }
    return near;
}

const char *ydoc_node_kind(const yaml_node_t *n)
{
    switch (n->type) {
    case YAML_MAPPING_NODE:
        return "a mapping";
    case YAML_SEQUENCE_NODE:
        return "a list";
    default:
        return "a scalar";
    }
}

int ynull(const yaml_node_t *n)
{
    if (!n || n->type != YAML_SCALAR_NODE)
        return 0;
    const char *tag = (const char *)n->tag, *s = (const char *)n->data.scalar.value;
    if (tag && strcmp(tag, YAML_NULL_TAG) == 0)
        return 1;
    if (yquoted(n) || (tag && strcmp(tag, YAML_DEFAULT_SCALAR_TAG) != 0)) /* "~", !!str ~ */
        return 0;
    return !*s || !strcmp(s, "~") || !strcmp(s, "null") || !strcmp(s, "Null") || !strcmp(s, "NULL");
}

/* The i-th pair of mapping n as written, null values included. */
static int pair_raw(struct ydoc *d, yaml_node_t *n, int i, yaml_node_t **key, yaml_node_t **val)
{
    if (!n || n->type != YAML_MAPPING_NODE)
        return 0;
    yaml_node_pair_t *p = n->data.mapping.pairs.start + i;
    if (i < 0 || p >= n->data.mapping.pairs.top)
        return 0;
    *key = yaml_document_get_node(&d->doc, p->key);
    *val = yaml_document_get_node(&d->doc, p->value);
    return *key && *val;
}

int ymap_pair(struct ydoc *d, yaml_node_t *n, int i, yaml_node_t **key, yaml_node_t **val)
{
    if (i < 0)
        return 0;
    for (int raw = 0, seen = 0; pair_raw(d, n, raw, key, val); raw++)
        if (!ynull(*val) && seen++ == i)
            return 1;
    return 0;
}

#define SPACING_NOTE "the points' minimum spacing in a 100x100 domain, 0 < t <= 100"
#define SPP_NOTE                                                                                             \
    "the samples per pixel follow from it, " SPACING_NOTE ": 5 gives 400, 1 gives 10000 with a grid sampler"
#define LIGHT_NOTE "a light's points per set follow from it, " SPACING_NOTE

/* Words other renderers and formats use for our keys, which edit distance cannot find ("spp"
   is nowhere near "threshold"), for the "did you mean" of job and scene keys alike. A word is
   offered only where its key is allowed (the first such), before any near miss ("samples" is
   nearer "sampler"); note, when set, says what the key means. */
static const struct {
    const char *word, *key, *note;
} synonyms[] = {
    {"color", "albedo", NULL},
    {"colour", "albedo", NULL},
    {"diffuse", "albedo", NULL},
    {"base_color", "albedo", NULL},
    {"emission", "emit", NULL},
    {"emissive", "emit", NULL},
    {"emittance", "emit", NULL},
    {"intensity", "emit", NULL},
    {"ref_idx", "ior", NULL},
    {"eta", "ior", NULL},
    {"refraction_index", "ior", NULL},
    {"roughness", "fuzz", NULL},
    {"spp", "threshold", SPP_NOTE},
    {"samples", "threshold", SPP_NOTE},
    {"samples_per_pixel", "threshold", SPP_NOTE},
    {"light_spp", "light_threshold", LIGHT_NOTE},
    {"light_samples", "light_threshold", LIGHT_NOTE},
    {"depth", "max_depth", NULL},
    {"bounces", "max_depth", NULL},
    {"max_bounces", "max_depth", NULL},
    {"threads", "processes", NULL},
    {"workers", "processes", NULL},
    {"out", "output", NULL},
    {"filename", "output", NULL},
    {"filename", "file", NULL},
    {"position", "center", NULL},
    {"position", "lookfrom", NULL},
    {"eye", "lookfrom", NULL},
    {"target", "lookat", NULL},
    {"rotation", "rotate_y", NULL},
    {"translation", "translate", NULL},
    {"mat", "material", NULL},
    {"r", "radius", NULL},
    {"rad", "radius", NULL},
};

/* The "did you mean" for an unknown key name among allowed: a synonym's key (and in note what
   it means, or NULL), else a near miss; NULL when none fits. */
static const char *key_suggestion(const char *name, const char *const *allowed, const char **note)
{
    *note = NULL;
    for (size_t i = 0; i < sizeof synonyms / sizeof synonyms[0]; i++) {
        if (strcasecmp(synonyms[i].word, name) != 0)
            continue;
        for (const char *const *a = allowed; *a; a++)
            if (!strcmp(*a, synonyms[i].key)) {
                *note = synonyms[i].note;
                return *a;
            }
    }
    return ystr_nearest(name, allowed, -1);
}

int ymap_check(struct ydoc *d, yaml_node_t *n, const char *const *allowed, const char *what, struct err *e)
{
    if (!n || n->type != YAML_MAPPING_NODE)
        return ydoc_fail(d, n, e, "%s: expected a mapping of keys, got %s", what,
                         n ? ydoc_node_kind(n) : "nothing");
    yaml_node_t *k, *v;
    for (int i = 0; pair_raw(d, n, i, &k, &v); i++) {
        const char *name = yscalar(k);
        if (!name)
            return ydoc_fail(d, k, e, "%s: keys must be plain names, got %s", what, ydoc_node_kind(k));
        int known = 0;
        for (const char *const *a = allowed; *a; a++)
            known |= strcmp(*a, name) == 0;
        if (!known) {
            const char *note, *near = key_suggestion(name, allowed, &note);
            if (near)
                return ydoc_fail(d, k, e, "%s: unknown key in %s (did you mean \"%s\"?%s%s)", name, what,
                                 near, note ? " " : "", note ? note : "");
            return ydoc_fail(d, k, e, "%s: unknown key in %s", name, what);
        }
        yaml_node_t *k2, *v2;
        for (int j = 0; j < i && pair_raw(d, n, j, &k2, &v2); j++)
            if (yscalar(k2) && strcmp(yscalar(k2), name) == 0)
                return ydoc_fail(d, k, e, "%s: duplicate key in %s (first at line %d)", name, what,
                                 (int)k2->start_mark.line + 1);
    }
    return 0;
}

yaml_node_t *ymap_get_raw(struct ydoc *d, yaml_node_t *n, const char *key)
{
    yaml_node_t *k, *v;
    for (int i = 0; pair_raw(d, n, i, &k, &v); i++)
        if (yscalar(k) && strcmp(yscalar(k), key) == 0)
            return v;
    return NULL;
}

yaml_node_t *ymap_get(struct ydoc *d, yaml_node_t *n, const char *key)
{
    yaml_node_t *v = ymap_get_raw(d, n, key);
    return ynull(v) ? NULL : v;
}

int ymap_missing(struct ydoc *d, yaml_node_t *n, const char *key, struct err *e, const char *fmt, ...)
{
    yaml_node_t *v = ymap_get_raw(d, n, key);
    if (v && ynull(v))
        return ydoc_fail(d, v, e, "%s: needs a value (it is required), got %s", key,
                         *yscalar(v) ? yscalar(v) : "nothing");
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return ydoc_fail(d, n, e, "%s", msg);
}

int yseq_len(yaml_node_t *n)
{
    if (!n || n->type != YAML_SEQUENCE_NODE)
        return -1;
    return (int)(n->data.sequence.items.top - n->data.sequence.items.start);
}

yaml_node_t *yseq_item(struct ydoc *d, yaml_node_t *n, int i)
{
    if (i < 0 || i >= yseq_len(n))
        return NULL;
    return yaml_document_get_node(&d->doc, n->data.sequence.items.start[i]);
}

int yquoted(const yaml_node_t *n)
{
    return n && n->type == YAML_SCALAR_NODE && n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE &&
           n->data.scalar.style != YAML_ANY_SCALAR_STYLE;
}
