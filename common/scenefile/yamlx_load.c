/* yamlx_load: a YAML file or text into a ydoc with libyaml's document API: one document, its
   shape bounded (depth, nodes, alias expansion), its merge keys expanded. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fileio.h"
#include "yamlx.h"

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
        const int line = (int)ev.start_mark.line + 1, col = (int)ev.start_mark.column + 1;
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
                rc = err_set(e, path, line, col, "nesting deeper than %d levels", YDOC_MAX_DEPTH);
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
                        rc = err_set(e, path, line, col, "out of memory");
                        break;
                    }
                    d->str_tagged = grown;
                }
                d->str_tagged[d->n_str_tagged++] = ev.start_mark.index;
            }
            break;
        case YAML_ALIAS_EVENT:
            if (++aliases > YDOC_MAX_ALIASES)
                rc = err_set(e, path, line, col, "more than %d aliases", YDOC_MAX_ALIASES);
            break;
        default:
            break;
        }
        if (rc == 0 && anchor && ++anchors > YDOC_MAX_ANCHORS)
            rc = err_set(e, path, line, col, "more than %d anchors (&name)", YDOC_MAX_ANCHORS);
        yaml_event_delete(&ev);
    }
    yaml_parser_delete(&p);
    return rc;
}

/* p's syntax error at its place: libyaml's reader (bad UTF-8, a control character) leaves
   problem_mark unset and gives the byte offset alone, so its line and column are counted here. */
static int syntax_error(const yaml_parser_t *p, const uint8_t *data, size_t len, const char *path,
                        struct err *e)
{
    int line = (int)p->problem_mark.line + 1, col = (int)p->problem_mark.column + 1;
    if (p->error == YAML_READER_ERROR) {
        line = col = 1;
        for (size_t i = 0; i < p->problem_offset && i < len; i++, col++)
            if (data[i] == '\n')
                line++, col = 0;
    }
    const char *what = p->problem ? p->problem : "error";
    if (p->context)
        return err_set(e, path, line, col, "YAML syntax error: %s %s", what, p->context);
    return err_set(e, path, line, col, "YAML syntax error: %s", what);
}

/* A job or scene file holds one YAML document: a second one (after "---") would be silently
   ignored, so it is an error at its start, as is a syntax error in it. Empty documents (a bare
   "---") are skipped, up to the end of the stream: one may stand before a real second document.
   0 when there is none. */
static int no_second_document(yaml_parser_t *p, const uint8_t *data, size_t len, const char *path,
                              struct err *e)
{
    for (;;) {
        yaml_document_t next;
        if (!yaml_parser_load(p, &next))
            return syntax_error(p, data, len, path, e);
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

int ydoc_parse(struct ydoc *d, const char *name, const uint8_t *data, size_t len, struct err *e)
{
    memset(d, 0, sizeof *d);
    snprintf(d->file, sizeof d->file, "%s", name);
    if (check_events(d, data, len, name, e) < 0) {
        ydoc_free(d);
        return -1;
    }
    yaml_parser_t p;
    if (!yaml_parser_initialize(&p))
        return err_set(e, name, 0, 0, "out of memory starting the YAML parser");
    yaml_parser_set_input_string(&p, data, len);
    int rc = 0;
    if (!yaml_parser_load(&p, &d->doc)) {
        rc = syntax_error(&p, data, len, name, e);
    } else {
        d->loaded = 1;
        if (!yaml_document_get_root_node(&d->doc))
            rc = err_set(e, name, 1, 1, "empty file: expected a mapping of keys");
        else
            rc = check_shape(d, e);
        if (rc == 0)
            rc = ydoc_expand_merges(d, e);
        if (rc == 0)
            rc = no_second_document(&p, data, len, name, e);
        if (rc < 0) /* a failure leaves nothing to free */
            ydoc_free(d);
    }
    yaml_parser_delete(&p);
    return rc;
}

int ydoc_load(struct ydoc *d, const char *path, struct err *e)
{
    memset(d, 0, sizeof *d);
    snprintf(d->file, sizeof d->file, "%s", path);
    uint8_t *data = NULL;
    size_t len = 0;
    if (fileio_read_all(path, YDOC_MAX_BYTES, &data, &len, e) < 0)
        return -1;
    int rc = ydoc_parse(d, path, data, len, e);
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
