/* verdict_csv: summary.csv parsed in place, and a hash set of names, both in linear time. */
#include "verdict_csv.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/hash.h"

int verdict_csv_parse(struct verdict_csv *t, char *text, size_t len, const char *path, struct err *e)
{
    size_t lines = 1;
    *t = (struct verdict_csv){0};
    for (size_t i = 0; i < len; i++) {
        if (text[i] == 0)
            return err_set(e, path, (int)(lines < VERDICT_CSV_MAX_ROWS ? lines : VERDICT_CSV_MAX_ROWS), 0,
                           "a NUL byte (summary.csv is text)");
        lines += text[i] == '\n' || text[i] == '\r'; /* a row ends at either (CR alone too) */
    }
    size_t cap = lines < VERDICT_CSV_MAX_ROWS ? lines : VERDICT_CSV_MAX_ROWS;
    t->rows = calloc(cap, sizeof *t->rows);
    if (!t->rows)
        return err_set(e, path, 0, 0, "out of memory");
    char *r = text, *w = text; /* w never passes r: the unquoted text is never longer */
    while (*r) {
        if ((size_t)t->n_rows == cap) {
            verdict_csv_free(t);
            return err_set(e, path, VERDICT_CSV_MAX_ROWS + 1, 0, "more than %d rows", VERDICT_CSV_MAX_ROWS);
        }
        int nf = 0;
        for (;;) {
            char *start = w;
            if (*r == '"') {
                for (r++; *r && !(*r == '"' && r[1] != '"'); r++)
                    *w++ = *r == '"' ? *r++ : *r;
                r += *r == '"';
            }
            while (*r && *r != ',' && *r != '\n' && *r != '\r') /* unquoted, or text after a quote */
                *w++ = *r++;
            char end = *r;
            *w++ = 0;
            if (nf < VERDICT_CSV_FIELDS)
                t->rows[t->n_rows][nf] = start;
            nf++;
            r += end != 0;
            if (end != ',') {
                r += end == '\r' && *r == '\n';
                break;
            }
        }
        if (t->n_rows == 0)
            t->n_fields = nf;
        if (nf != t->n_fields || nf > VERDICT_CSV_FIELDS) {
            int row = t->n_rows + 1, header = t->n_fields;
            verdict_csv_free(t);
            return err_set(e, path, row, 0, "%d fields, the header has %d (at most %d read)", nf, header,
                           VERDICT_CSV_FIELDS);
        }
        t->n_rows++;
    }
    return 0;
}

int verdict_csv_figure(const char *s, double lo, double hi, double *x)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || errno == ERANGE || !isfinite(v) || v < lo || v > hi)
        return -1;
    *x = v;
    return 0;
}

int verdict_csv_product(size_t a, size_t b, size_t max, size_t *out)
{
    if (a != 0 && b > max / a)
        return -1;
    *out = a * b;
    return *out <= max ? 0 : -1;
}

void verdict_csv_free(struct verdict_csv *t)
{
    free(t->rows);
    *t = (struct verdict_csv){0};
}

int verdict_names_init(struct verdict_names *t, int cap)
{
    *t = (struct verdict_names){.cap = cap > 0 ? cap : 1};
    t->n_slots = 2;
    while (t->n_slots < 2 * (size_t)t->cap)
        t->n_slots *= 2;
    t->s = calloc((size_t)t->cap, sizeof *t->s);
    t->len = calloc((size_t)t->cap, sizeof *t->len);
    t->slot = calloc(t->n_slots, sizeof *t->slot);
    if (t->s && t->len && t->slot)
        return 0;
    verdict_names_free(t);
    return -1;
}

void verdict_names_free(struct verdict_names *t)
{
    free(t->s), free(t->len), free(t->slot);
    *t = (struct verdict_names){0};
}

int verdict_names_intern(struct verdict_names *t, const char *s, size_t len)
{
    size_t mask = t->n_slots - 1, i = (size_t)hash_bytes(HASH_FNV_OFFSET, s, len) & mask;
    for (; t->slot[i]; i = (i + 1) & mask) { /* linear probing: at most half the slots are full */
        int k = t->slot[i] - 1;
        if (t->len[k] == len && !memcmp(t->s[k], s, len))
            return k;
    }
    if (t->n == t->cap)
        return -1;
    t->s[t->n] = s, t->len[t->n] = len;
    t->slot[i] = ++t->n;
    return t->n - 1;
}
