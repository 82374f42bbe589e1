/* sbuf: a growing text buffer with printf and base64, and the one place names are made safe: the
   terminal sanitiser (sbuf_shown, sbuf_show) and the XML/SVG/HTML (sbuf_escape) and CSV (sbuf_csv)
   escapers; JSON's is json.h's, on the same UTF-8 rules (sbuf_utf8_len). */
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

/* Append the n bytes at s as they are (no format to scan: the JSON writer's per-character path). */
void sbuf_put(struct sbuf *b, const char *s, size_t n);

/* Length of the well-formed UTF-8 sequence at s (RFC 3629: no overlong forms, surrogates or code
   points over U+10FFFF), or 0 when the byte at s begins none. */
int sbuf_utf8_len(const char *s);

/* The code point of the well-formed UTF-8 sequence of n bytes at s. */
unsigned sbuf_code_point(const char *s, int n);

/* The terminal sanitiser, for every name (a file's, a folder's, a scene's, a variant's) and every
   line holding one shown on a terminal: s as is, but each control character (C0, DEL and the C1
   controls U+0080..U+009F, which terminals obey as escapes) shown as \n, \t, \r or \xNN per
   byte, and each byte not part of well-formed UTF-8 as \xNN. Appended to b. */
void sbuf_shown(struct sbuf *b, const char *s);

/* sbuf_shown into out (n bytes, NUL-ended, cut before a character that does not fit); returns out,
   for printf. A name of k bytes needs at most 4k + 1. */
const char *sbuf_show(const char *s, char *out, size_t n);

/* The XML, SVG and HTML escaper (text and attribute values): s as sbuf_shown shows it (control
   characters, which XML 1.0 forbids even as references, as \xNN text), with & < > " ' as
   entities. */
void sbuf_escape(struct sbuf *b, const char *s);

/* The CSV escaper (RFC 4180), lossless: s as is when it holds no comma, quote, CR or LF, else
   quoted with each quote doubled. */
void sbuf_csv(struct sbuf *b, const char *s);

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
