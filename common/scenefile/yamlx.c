/* yamlx: loading YAML with libyaml's document API and reading it with file:line:col errors. */
#include "yamlx.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/fileio.h"

/* Number of children of a collection node (0 for scalars). */
static long child_count(const yaml_node_t *n)
{
    if (n->type == YAML_SEQUENCE_NODE)
        return n->data.sequence.items.top - n->data.sequence.items.start;
    if (n->type == YAML_MAPPING_NODE)
        return n->data.mapping.pairs.top - n->data.mapping.pairs.start;
    return 0;
}

static yaml_node_t *child(struct ydoc *d, const yaml_node_t *n, long i)
{
    int id = n->type == YAML_SEQUENCE_NODE ? n->data.sequence.items.start[i]
                                           : n->data.mapping.pairs.start[i].value;
    return yaml_document_get_node(&d->doc, id);
}

/* Refuse documents that nest deeper than YDOC_MAX_DEPTH, hold more than YDOC_MAX_NODES nodes,
   or whose aliases would expand past YDOC_MAX_VISITS node visits ("billion laughs"), so our
   loaders never meet them. Depth-first with an explicit, bounded stack. */
static int check_shape(struct ydoc *d, struct err *e)
{
    struct frame {
        yaml_node_t *n;
        long next;
    } stack[YDOC_MAX_DEPTH];
    long nodes = d->doc.nodes.top - d->doc.nodes.start, visits = 1;
    if (nodes > YDOC_MAX_NODES)
        return ydoc_fail(d, ydoc_root(d), e, "document has %ld nodes (limit %d)", nodes, YDOC_MAX_NODES);
    int sp = 0;
    stack[sp++] = (struct frame){ydoc_root(d), 0};
    while (sp > 0) {
        struct frame *f = &stack[sp - 1];
        if (!f->n || f->next >= child_count(f->n)) {
            sp--;
            continue;
        }
        yaml_node_t *c = child(d, f->n, f->next++);
        if (!c)
            continue;
        if (++visits > YDOC_MAX_VISITS)
            return ydoc_fail(d, c, e, "document expands past %d nodes through aliases", YDOC_MAX_VISITS);
        if (child_count(c) == 0)
            continue;
        if (sp >= YDOC_MAX_DEPTH)
            return ydoc_fail(d, c, e, "nesting deeper than %d levels", YDOC_MAX_DEPTH);
        stack[sp++] = (struct frame){c, 0};
    }
    return 0;
}

/* Walk the stream's events before anything is composed, and refuse one that nests deeper than
   YDOC_MAX_DEPTH or holds more than YDOC_MAX_ANCHORS anchors or YDOC_MAX_ALIASES aliases, at the
   offending event. libyaml's composer (yaml_parser_load) takes time quadratic in the depth and in
   the anchors (each anchor and alias is looked up in a list), so a 200k-bracket `[[[...]]]` ran
   for minutes before check_shape could see it; the events arrive one at a time, and the scanner
   reads only a bounded way ahead, so this stops within microseconds of the limit. Syntax errors
   are left to the load that follows (same parser, same message). 0 when within bounds. */
static int check_events(struct ydoc *d, const uint8_t *data, size_t len, const char *path, struct err *e)
{
    size_t cap = 0;
    yaml_parser_t p;
    if (!yaml_parser_initialize(&p))
        return err_set(e, path, 0, 0, "out of memory starting the YAML parser");
    yaml_parser_set_input_string(&p, data, len);
    int depth = 0, rc = 0;
    long anchors = 0, aliases = 0;
    for (int done = 0; !done && rc == 0;) {
        yaml_event_t ev;
        if (!yaml_parser_parse(&p, &ev))
            break;
        const yaml_mark_t *m = &ev.start_mark;
        const char *anchor = NULL;
        switch (ev.type) {
        case YAML_STREAM_END_EVENT:
            done = 1;
            break;
        case YAML_SEQUENCE_START_EVENT:
        case YAML_MAPPING_START_EVENT:
            anchor = ev.type == YAML_SEQUENCE_START_EVENT ? (const char *)ev.data.sequence_start.anchor
                                                          : (const char *)ev.data.mapping_start.anchor;
            if (++depth > YDOC_MAX_DEPTH)
                rc = err_set(e, path, (int)m->line + 1, (int)m->column + 1, "nesting deeper than %d levels",
                             YDOC_MAX_DEPTH);
            break;
        case YAML_SEQUENCE_END_EVENT:
        case YAML_MAPPING_END_EVENT:
            depth--;
            break;
        case YAML_SCALAR_EVENT:
            anchor = (const char *)ev.data.scalar.anchor;
            if (ev.data.scalar.tag && !strcmp((const char *)ev.data.scalar.tag, YAML_STR_TAG)) {
                if ((size_t)d->n_str_tagged == cap) {
                    size_t *grown = realloc(d->str_tagged, (cap = cap ? 2 * cap : 16) * sizeof *grown);
                    if (!grown) {
                        rc = err_set(e, path, (int)m->line + 1, (int)m->column + 1, "out of memory");
                        break;
                    }
                    d->str_tagged = grown;
                }
                d->str_tagged[d->n_str_tagged++] = m->index;
            }
            break;
        case YAML_ALIAS_EVENT:
            if (++aliases > YDOC_MAX_ALIASES)
                rc = err_set(e, path, (int)m->line + 1, (int)m->column + 1, "more than %d aliases",
                             YDOC_MAX_ALIASES);
            break;
        default:
            break;
        }
        if (rc == 0 && anchor && ++anchors > YDOC_MAX_ANCHORS)
            rc = err_set(e, path, (int)m->line + 1, (int)m->column + 1, "more than %d anchors (&name)",
                         YDOC_MAX_ANCHORS);
        yaml_event_delete(&ev);
    }
    yaml_parser_delete(&p);
    return rc;
}

/* A job or scene file holds one YAML document: a second one (after "---") would be silently
   ignored, so it is an error at its start, as is a syntax error in it. Empty documents (a bare
   "---") are skipped, up to the end of the stream: one may stand before a real second document.
   0 when there is none. */
static int no_second_document(yaml_parser_t *p, const char *path, struct err *e)
{
    for (;;) {
        yaml_document_t next;
        if (!yaml_parser_load(p, &next)) {
            const yaml_mark_t *m = &p->problem_mark;
            return err_set(e, path, (int)m->line + 1, (int)m->column + 1, "YAML syntax error: %s",
                           p->problem ? p->problem : "error");
        }
        const yaml_node_t *root = yaml_document_get_root_node(&next);
        int empty = root && root->type == YAML_SCALAR_NODE && root->data.scalar.length == 0 &&
                    root->data.scalar.style == YAML_PLAIN_SCALAR_STYLE;
        int rc = root && !empty
                     ? err_set(e, path, (int)next.start_mark.line + 1, (int)next.start_mark.column + 1,
                               "a second YAML document: a file holds one job or one scene "
                               "(one document)")
                     : 0;
        yaml_document_delete(&next);
        if (rc < 0 || !root) /* no root: the end of the stream */
            return rc;
    }
}

int ydoc_load(struct ydoc *d, const char *path, struct err *e)
{
    memset(d, 0, sizeof *d);
    snprintf(d->file, sizeof d->file, "%s", path);
    uint8_t *data = NULL;
    size_t len = 0;
    if (fileio_read_all(path, YDOC_MAX_BYTES, &data, &len, e) < 0)
        return -1;
    if (check_events(d, data, len, path, e) < 0) {
        free(data);
        return -1;
    }
    yaml_parser_t p;
    if (!yaml_parser_initialize(&p)) {
        free(data);
        return err_set(e, path, 0, 0, "out of memory starting the YAML parser");
    }
    yaml_parser_set_input_string(&p, data, len);
    int rc = 0;
    if (!yaml_parser_load(&p, &d->doc)) {
        const yaml_mark_t *m = &p.problem_mark;
        if (p.context)
            err_set(e, path, (int)m->line + 1, (int)m->column + 1, "YAML syntax error: %s %s",
                    p.problem ? p.problem : "error", p.context);
        else
            err_set(e, path, (int)m->line + 1, (int)m->column + 1, "YAML syntax error: %s",
                    p.problem ? p.problem : "error");
        rc = -1;
    } else {
        d->loaded = 1;
        if (!yaml_document_get_root_node(&d->doc))
            rc = err_set(e, path, 1, 1, "empty file: expected a mapping of keys");
        else
            rc = check_shape(d, e);
        if (rc == 0)
            rc = ydoc_expand_merges(d, e);
        if (rc == 0)
            rc = no_second_document(&p, path, e);
        if (rc < 0) /* a failure leaves nothing to free */
            ydoc_free(d);
    }
    yaml_parser_delete(&p);
    free(data);
    return rc;
}

void ydoc_free(struct ydoc *d)
{
    if (d->loaded)
        yaml_document_delete(&d->doc);
    d->loaded = 0;
    free(d->str_tagged);
    d->str_tagged = NULL;
    d->n_str_tagged = 0;
}

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

int ystr_distance(const char *a, const char *b)
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
