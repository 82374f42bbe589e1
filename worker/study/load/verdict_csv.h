/* verdict_csv: summary.csv's text as rows of fields (RFC 4180), and names interned whole in
   linear time, for verdict_load. Every count it returns is bounded before anything is allocated
   from it. */
#ifndef VERDICT_CSV_H
#define VERDICT_CSV_H

#include <stddef.h>

#include "base/err.h"

/* Most fields a row may have (summary.csv: 41 with a suite's study column, flip, the work counts
   and a column per render_spec row), and most rows (the header included) one file may have: a suite of up to
   64 studies of 4096 images each, with room. */
#define VERDICT_CSV_FIELDS 48
#define VERDICT_CSV_MAX_ROWS (64 * 4096 + 1)

/* Rows of field pointers into one buffer of unquoted, NUL-ended fields; row 0 is the header. */
struct verdict_csv {
    char *(*rows)[VERDICT_CSV_FIELDS];
    int n_rows, n_fields; /* n_fields: the header's, every row's */
};

/* Parse text (len bytes, NUL-ended; rewritten in place and pointed into: keep it while t is used).
   A quoted field's "" is one quote; a row ends at LF, CR or CRLF. 0, or -1 with e at path:row
   (a row of another width, more than VERDICT_CSV_FIELDS fields or VERDICT_CSV_MAX_ROWS rows, a
   NUL byte). Free with verdict_csv_free. */
int verdict_csv_parse(struct verdict_csv *t, char *text, size_t len, const char *path, struct err *e);
void verdict_csv_free(struct verdict_csv *t);

/* A field as a figure: the whole of s a finite decimal number in [lo, hi], into *x. 0, else -1
   (text, inf, nan, out of range: the caller leaves it out and says so). */
int verdict_csv_figure(const char *s, double lo, double hi, double *x);

/* A count's product: a * b into *out when it is at most max (in size_t, checked before it could
   wrap), else -1. */
int verdict_csv_product(size_t a, size_t b, size_t max, size_t *out);

/* A set of names, each an index in first-seen order: a hash table over (pointer, length) keys,
   which must stay valid while the set is used. Names are compared whole, never cut. */
struct verdict_names {
    const char **s;
    size_t *len;
    int *slot; /* index + 1, or 0 for empty; n_slots a power of two at least twice cap */
    size_t n_slots;
    int n, cap;
};

/* An empty set for at most cap names. 0, or -1 when out of memory. */
int verdict_names_init(struct verdict_names *t, int cap);
void verdict_names_free(struct verdict_names *t);

/* The index of the name s[0..len), added when absent; -1 when the set already holds cap names. */
int verdict_names_intern(struct verdict_names *t, const char *s, size_t len);

#endif
