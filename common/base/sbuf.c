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

void sbuf_put(struct sbuf *b, const char *s, size_t n)
{
    if (reserve(b, n) < 0)
        return;
    memcpy(b->buf + b->len, s, n);
    b->len += n;
    b->buf[b->len] = '\0';
}

int sbuf_utf8_len(const char *s)
{
    const unsigned char *c = (const unsigned char *)s;
    int n = c[0] < 0x80                    ? 1
            : c[0] >= 0xc2 && c[0] <= 0xdf ? 2
            : c[0] >= 0xe0 && c[0] <= 0xef ? 3
            : c[0] >= 0xf0 && c[0] <= 0xf4 ? 4
                                           : 0;
    for (int i = 1; i < n; i++)
        if ((c[i] & 0xc0) != 0x80)
            return 0;
    if ((c[0] == 0xe0 && c[1] < 0xa0) || (c[0] == 0xed && c[1] > 0x9f) || (c[0] == 0xf0 && c[1] < 0x90) ||
        (c[0] == 0xf4 && c[1] > 0x8f))
        return 0;
    return n;
}

unsigned sbuf_code_point(const char *s, int n)
{
    const unsigned char *c = (const unsigned char *)s;
    unsigned cp = n == 1 ? c[0] : c[0] & (0x7f >> n);
    for (int i = 1; i < n; i++)
        cp = cp << 6 | (c[i] & 0x3f);
    return cp;
}

/* The character at s as the terminal sanitiser shows it, into out (at most 17 bytes with the NUL:
   four \xNN); its length in s into *len. 0 when it is shown as it is (out untouched). */
static int shown_char(const char *s, char out[17], int *len)
{
    int n = sbuf_utf8_len(s);
    *len = n ? n : 1;
    unsigned cp = n ? sbuf_code_point(s, n) : 0;
    if (n && !(cp < 0x20 || cp == 0x7f || (cp >= 0x80 && cp <= 0x9f) || cp == 0xfffe || cp == 0xffff))
        return 0;
    if (cp == '\n' || cp == '\t' || cp == '\r') {
        snprintf(out, 17, "\\%c", cp == '\n' ? 'n' : cp == '\t' ? 't' : 'r');
        return 1;
    }
    size_t k = 0;
    for (int i = 0; i < *len; i++)
        k += (size_t)snprintf(out + k, 17 - k, "\\x%02x", (unsigned char)s[i]);
    return 1;
}

/* s through the terminal sanitiser, and with html its markup characters as entities too. */
static void append_shown(struct sbuf *b, const char *s, int html)
{
    char esc[17];
    for (int len; *s; s += len) {
        const char *as = shown_char(s, esc, &len) ? esc
                         : !html                  ? NULL
                         : *s == '&'              ? "&amp;"
                         : *s == '<'              ? "&lt;"
                         : *s == '>'              ? "&gt;"
                         : *s == '"'              ? "&quot;"
                         : *s == '\''             ? "&#39;"
                                                  : NULL;
        if (as)
            sbuf_printf(b, "%s", as);
        else
            sbuf_printf(b, "%.*s", len, s);
    }
}

void sbuf_shown(struct sbuf *b, const char *s)
{
    append_shown(b, s, 0);
}

const char *sbuf_show(const char *s, char *out, size_t n)
{
    char esc[17];
    size_t k = 0;
    if (n == 0)
        return out;
    for (int len; *s; s += len) {
        const char *piece = shown_char(s, esc, &len) ? esc : s;
        size_t pl = piece == esc ? strlen(esc) : (size_t)len;
        if (k + pl >= n)
            break;
        memcpy(out + k, piece, pl);
        k += pl;
    }
    out[k] = 0;
    return out;
}

void sbuf_escape(struct sbuf *b, const char *s)
{
    append_shown(b, s, 1);
}

void sbuf_csv(struct sbuf *b, const char *s)
{
    if (!strpbrk(s, ",\"\r\n")) {
        sbuf_printf(b, "%s", s);
        return;
    }
    sbuf_printf(b, "\"");
    for (const char *p = s; *p; p++)
        sbuf_printf(b, "%s%c", *p == '"' ? "\"" : "", *p); /* a quote is doubled */
    sbuf_printf(b, "\"");
}

void sbuf_base64(struct sbuf *b, const uint8_t *data, size_t len)
{
    static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    if (reserve(b, (len + 2) / 3 * 4) < 0)
        return;
    char *o = b->buf + b->len;
    for (size_t i = 0; i < len; i += 3) { /* a last group of one or two bytes is padded with '=' */
        uint32_t v = (uint32_t)data[i] << 16 | (i + 1 < len ? (uint32_t)data[i + 1] << 8 : 0) |
                     (i + 2 < len ? data[i + 2] : 0);
        *o++ = tab[v >> 18];
        *o++ = tab[(v >> 12) & 63];
        *o++ = i + 1 < len ? tab[(v >> 6) & 63] : '=';
        *o++ = i + 2 < len ? tab[v & 63] : '=';
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
