/* yamlx_merge: YAML merge keys (`<<: *defaults`), which libyaml leaves to its callers. */
#include <stdlib.h>
#include <string.h>

#include "yamlx.h"

/* A mapping's merge state while expanding: not yet, in progress (a loop), done. */
enum { MERGE_PENDING, MERGE_BUSY, MERGE_DONE };

struct merge {
    struct ydoc *d;
    unsigned char *state; /* per node id - 1 */
    long work;            /* keys compared and pairs copied so far, bounded by YDOC_MAX_VISITS */
    struct err *e;
};

static int is_merge_key(const yaml_node_t *k)
{
    return k && k->type == YAML_SCALAR_NODE && k->data.scalar.style == YAML_PLAIN_SCALAR_STYLE &&
           !strcmp((const char *)k->data.scalar.value, "<<");
}

static int has_key(struct merge *mg, const yaml_node_t *m, const char *key)
{
    struct ydoc *d = mg->d;
    mg->work += m->data.mapping.pairs.top - m->data.mapping.pairs.start;
    for (yaml_node_pair_t *p = m->data.mapping.pairs.start; p < m->data.mapping.pairs.top; p++) {
        const char *s = yscalar(yaml_document_get_node(&d->doc, p->key));
        if (s && !strcmp(s, key))
            return 1;
    }
    return 0;
}

static int expand(struct merge *mg, int id, int depth);

/* Append to mapping `id` the pairs of mapping `src` whose keys it lacks (its own keys, and those
   of earlier sources, win: YAML 1.1's merge key). */
static int merge_from(struct merge *mg, int id, yaml_node_t *src, int depth)
{
    struct ydoc *d = mg->d;
    if (!src || src->type != YAML_MAPPING_NODE)
        return ydoc_fail(d, src, mg->e, "<<: a merge key takes a mapping or a list of mappings");
    int src_id = (int)(src - d->doc.nodes.start) + 1;
    if (expand(mg, src_id, depth + 1) < 0)
        return -1;
    long n = src->data.mapping.pairs.top - src->data.mapping.pairs.start;
    for (long i = 0; i < n; i++) {
        yaml_node_pair_t p = src->data.mapping.pairs.start[i]; /* a copy: appending may move them */
        yaml_node_t *m = yaml_document_get_node(&d->doc, id);
        const char *key = yscalar(yaml_document_get_node(&d->doc, p.key));
        int taken = key && has_key(mg, m, key);
        /* a bound on the work, not only on the pairs: each copy first scans the keys so far */
        if (++mg->work > YDOC_MAX_VISITS)
            return ydoc_fail(d, m, mg->e, "<<: merge keys too large to expand (over %d entries compared)",
                             YDOC_MAX_VISITS);
        if (taken)
            continue;
        if (!yaml_document_append_mapping_pair(&d->doc, id, p.key, p.value))
            return ydoc_fail(d, m, mg->e, "out of memory expanding a merge key");
    }
    return 0;
}

/* Expand the merge keys of node `id` (a no-op for anything but a mapping holding one): its `<<`
   pairs are taken out, then their mappings' entries added. Sources are expanded first. */
static int expand(struct merge *mg, int id, int depth)
{
    struct ydoc *d = mg->d;
    yaml_node_t *m = yaml_document_get_node(&d->doc, id);
    if (!m || m->type != YAML_MAPPING_NODE || mg->state[id - 1] == MERGE_DONE)
        return 0;
    if (mg->state[id - 1] == MERGE_BUSY || depth > YDOC_MAX_DEPTH)
        return ydoc_fail(d, m, mg->e, "<<: merge keys that loop or nest deeper than %d", YDOC_MAX_DEPTH);
    mg->state[id - 1] = MERGE_BUSY;
    /* Take the merge pairs out (keeping the others in order), remembering their values. */
    long n = m->data.mapping.pairs.top - m->data.mapping.pairs.start, kept = 0, nsrc = 0;
    int *src = n ? malloc((size_t)n * sizeof *src) : NULL;
    if (n && !src)
        return ydoc_fail(d, m, mg->e, "out of memory expanding a merge key");
    yaml_node_t *first = NULL; /* the mapping's << key: a second one is a duplicate key */
    for (long i = 0; i < n; i++) {
        yaml_node_pair_t p = m->data.mapping.pairs.start[i];
        yaml_node_t *k = yaml_document_get_node(&d->doc, p.key);
        if (is_merge_key(k) && first) {
            free(src);
            return ydoc_fail(d, k, mg->e,
                             "<<: duplicate key (first at line %d; merge several with <<: [*a, *b])",
                             (int)first->start_mark.line + 1);
        }
        if (is_merge_key(k))
            first = k, src[nsrc++] = p.value;
        else
            m->data.mapping.pairs.start[kept++] = p;
    }
    m->data.mapping.pairs.top = m->data.mapping.pairs.start + kept;
    int rc = 0;
    for (long s = 0; s < nsrc && rc == 0; s++) {
        yaml_node_t *v = yaml_document_get_node(&d->doc, src[s]);
        if (v && v->type == YAML_SEQUENCE_NODE) {
            for (int i = 0; i < yseq_len(v) && rc == 0; i++)
                rc = merge_from(mg, id, yseq_item(d, v, i), depth);
        } else if (v) {
            rc = merge_from(mg, id, v, depth);
        }
    }
    free(src);
    mg->state[id - 1] = MERGE_DONE;
    return rc;
}

int ydoc_expand_merges(struct ydoc *d, struct err *e)
{
    long nodes = d->doc.nodes.top - d->doc.nodes.start;
    struct merge mg = {d, calloc((size_t)nodes + 1, 1), 0, e};
    if (!mg.state)
        return err_set(e, d->file, 0, 0, "out of memory expanding merge keys");
    int rc = 0;
    for (long id = 1; id <= nodes && rc == 0; id++)
        rc = expand(&mg, (int)id, 0);
    free(mg.state);
    return rc;
}
