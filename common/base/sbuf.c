/* sbuf: appending formatted, escaped and base64 text to a buffer that doubles as it fills. */
#include "sbuf.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Make room for at least `more` bytes plus the NUL. 0, or -1 (and oom) on no memory. */
static int reserve(struct sbuf *b, size_t more)
{
    if (b->oom)
        return -1;
    if (b->len + more + 1 <= b->cap)
        return 0;
    size_t cap = b->cap ? b->cap : 256;
    while (cap < b->len + more + 1)
        cap *= 2;
    char *p = realloc(b->buf, cap);
    if (!p) {
        b->oom = 1;
        return -1;
    }
    b->buf = p;
    b->cap = cap;
    return 0;
}

void sbuf_printf(struct sbuf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0 || reserve(b, (size_t)n) < 0)
        return;
    va_start(ap, fmt);
    vsnprintf(b->buf + b->len, (size_t)n + 1, fmt, ap);
    va_end(ap);
    b->len += (size_t)n;
}

void sbuf_escape(struct sbuf *b, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&':
            sbuf_printf(b, "&amp;");
            break;
        case '<':
            sbuf_printf(b, "&lt;");
            break;
        case '>':
            sbuf_printf(b, "&gt;");
            break;
        case '"':
            sbuf_printf(b, "&quot;");
            break;
        case '\'':
            sbuf_printf(b, "&#39;");
            break;
        default:
            sbuf_printf(b, "%c", *s);
        }
    }
}

void sbuf_base64(struct sbuf *b, const uint8_t *data, size_t len)
{
    static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    if (reserve(b, (len + 2) / 3 * 4) < 0)
        return;
    char *o = b->buf + b->len;
    size_t i = 0;
    for (; i + 3 <= len; i += 3) {
        uint32_t v = (uint32_t)data[i] << 16 | (uint32_t)data[i + 1] << 8 | data[i + 2];
        *o++ = tab[v >> 18];
        *o++ = tab[(v >> 12) & 63];
        *o++ = tab[(v >> 6) & 63];
        *o++ = tab[v & 63];
    }
    if (i < len) {
        uint32_t v = (uint32_t)data[i] << 16 | (i + 1 < len ? (uint32_t)data[i + 1] << 8 : 0);
        *o++ = tab[v >> 18];
        *o++ = tab[(v >> 12) & 63];
        *o++ = i + 1 < len ? tab[(v >> 6) & 63] : '=';
        *o++ = '=';
    }
    *o = 0;
    b->len = (size_t)(o - b->buf);
}

char *sbuf_take(struct sbuf *b)
{
    char *p = b->oom ? NULL : b->buf;
    if (b->oom)
        free(b->buf);
    memset(b, 0, sizeof *b);
    return p;
}

void sbuf_free(struct sbuf *b)
{
    free(b->buf);
    memset(b, 0, sizeof *b);
}
