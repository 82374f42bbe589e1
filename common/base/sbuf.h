/* sbuf: a growing text buffer with printf, XML/HTML escaping and base64 (for CSV, SVG, HTML). */
#ifndef SBUF_H
#define SBUF_H

#include <stddef.h>
#include <stdint.h>

/* Zero-initialise ({0}) to start; buf is NUL-terminated once anything was written. After an
   allocation failure oom is set and further writes are ignored. */
struct sbuf {
    char *buf;
    size_t len, cap;
    int oom;
};

/* Append printf-formatted text. */
void sbuf_printf(struct sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Append s with & < > " ' escaped for XML and HTML text and attribute values. */
void sbuf_escape(struct sbuf *b, const char *s);

/* Append len bytes of data as base64 (RFC 4648, with padding). */
void sbuf_base64(struct sbuf *b, const uint8_t *data, size_t len);

/* Hand the text to the caller (malloc'd; NULL after oom or when empty) and reset b. */
char *sbuf_take(struct sbuf *b);

/* Release b's memory (accepts a zeroed or taken buffer). */
void sbuf_free(struct sbuf *b);

/* "s" after a count other than one */
static inline const char *sbuf_plural(int n)
{
    return n == 1 ? "" : "s";
}

#endif
