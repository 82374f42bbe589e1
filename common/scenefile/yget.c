/* yget: typed reads of YAML scalars (numbers, booleans, strings, vectors) with file:line:col errors. */
#include "yget.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Show a scalar in a message, shortened and quoted. */
static void shown(yaml_node_t *n, char *buf, size_t len)
{
    const char *s = yscalar(n);
    if (!s) {
        snprintf(buf, len, "%s", ydoc_node_kind(n));
        return;
    }
    snprintf(buf, len, "\"%.40s%s\"", s, strlen(s) > 40 ? "..." : "");
}

/* 0, -1 (not a finite number), or -2: a number too close to zero for a double's normal range
   (strtod's underflow, a subnormal or 0 for a non-zero text). */
static int parse_double(const char *s, double *out)
{
    if (!s || !*s)
        return -1;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (*end || end == s || !isfinite(v))
        return -1;
    if (errno == ERANGE)
        return fabs(v) <= DBL_MIN ? -2 : -1;
    /* strtod accepts "nan", "inf" and hex; a user writing those meant something else. */
    for (const char *c = s; *c; c++)
        if (!strchr("0123456789+-.eE", *c))
            return -1;
    *out = v;
    return 0;
}

int yget_double(struct ydoc *d, yaml_node_t *n, const char *key, double *out, struct err *e)
{
    char buf[64];
    shown(n, buf, sizeof buf);
    int rc = parse_double(yscalar(n), out);
    if (rc == -2) {
        ydoc_fail(d, n, e, "%s: %s is too close to 0 for a double (below %g): give 0 or a larger number", key,
                  buf, DBL_MIN);
        return YGET_UNDERFLOW;
    }
    if (rc < 0)
        return ydoc_fail(d, n, e, "%s: must be a finite number, got %s", key, buf);
    if (yquoted(n))
        return ydoc_fail(d, n, e, "%s: must be a finite number, got %s" YQUOTED_NOTE, key, buf);
    if (ystr_tagged(d, n))
        return ydoc_fail(d, n, e, "%s: must be a finite number, got %s" YSTR_TAGGED_NOTE, key, buf);
    if (d->max_abs > 0 && fabs(*out) > d->max_abs)
        return ydoc_fail(d, n, e,
                         "%s: must be within [-%g, %g], got %s (the renderer keeps bounds and colours in "
                         "float)",
                         key, d->max_abs, d->max_abs, buf);
    return 0;
}

int yget_long(struct ydoc *d, yaml_node_t *n, const char *key, long lo, long hi, long *out, struct err *e)
{
    const char *s = yscalar(n);
    char buf[64];
    shown(n, buf, sizeof buf);
    char *end = NULL;
    errno = 0;
    long v = s && *s ? strtol(s, &end, 10) : 0;
    if (!s || !*s || *end || errno == ERANGE)
        return ydoc_fail(d, n, e, "%s: must be a whole number in [%ld, %ld], got %s", key, lo, hi, buf);
    if (yquoted(n))
        return ydoc_fail(d, n, e, "%s: must be a whole number in [%ld, %ld], got %s" YQUOTED_NOTE, key, lo,
                         hi, buf);
    if (ystr_tagged(d, n))
        return ydoc_fail(d, n, e, "%s: must be a whole number in [%ld, %ld], got %s" YSTR_TAGGED_NOTE, key,
                         lo, hi, buf);
    if (v < lo || v > hi)
        return ydoc_fail(d, n, e, "%s: must be in [%ld, %ld], got %s", key, lo, hi, buf);
    *out = v;
    return 0;
}

int yget_bool(struct ydoc *d, yaml_node_t *n, const char *key, int *out, struct err *e)
{
    const char *s = yscalar(n);
    char buf[64];
    shown(n, buf, sizeof buf);
    /* YAML 1.2's core schema: true, True, TRUE and the same for false (not 1.1's yes/no/on/off) */
    static const char *const truth[] = {"true", "True", "TRUE", "false", "False", "FALSE"};
    int which = -1;
    for (int i = 0; s && i < 6; i++)
        if (!strcmp(s, truth[i]))
            which = i;
    if (which >= 0) {
        if (yquoted(n) || ystr_tagged(d, n))
            return ydoc_fail(d, n, e,
                             "%s: must be true or false, got %s (a quoted string: write true or "
                             "false without quotes)",
                             key, buf);
        *out = which < 3;
        return 0;
    }
    return ydoc_fail(d, n, e, "%s: must be true or false, got %s", key, buf);
}

int yget_string(struct ydoc *d, yaml_node_t *n, const char *key, const char **out, struct err *e)
{
    const char *s = yscalar(n);
    if (!s || !*s) {
        char buf[64];
        shown(n, buf, sizeof buf);
        return ydoc_fail(d, n, e, "%s: must be a non-empty string, got %s", key, buf);
    }
    *out = s;
    return 0;
}

static int get_numbers(struct ydoc *d, yaml_node_t *n, const char *key, double *out, int count, struct err *e)
{
    if (yseq_len(n) != count) {
        char buf[64];
        shown(n, buf, sizeof buf);
        if (yseq_len(n) >= 0)
            snprintf(buf, sizeof buf, "a list of %d", yseq_len(n));
        return ydoc_fail(d, n, e, "%s: must be a list of %d numbers, got %s", key, count, buf);
    }
    for (int i = 0; i < count; i++)
        if (yget_double(d, yseq_item(d, n, i), key, &out[i], e) < 0)
            return -1;
    return 0;
}

int yget_vec3(struct ydoc *d, yaml_node_t *n, const char *key, vec3 *out, struct err *e)
{
    double v[3];
    if (get_numbers(d, n, key, v, 3, e) < 0)
        return -1;
    *out = v3(v[0], v[1], v[2]);
    return 0;
}

int yget_vec2(struct ydoc *d, yaml_node_t *n, const char *key, double out[2], struct err *e)
{
    return get_numbers(d, n, key, out, 2, e);
}
