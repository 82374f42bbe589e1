/* json: writing JSON text with escaping and pretty two-space indentation. */
#include "json.h"
#include "sbuf.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void json_init(struct json *j)
{
    memset(j, 0, sizeof *j);
    j->first[0] = 1;
}

void json_free(struct json *j)
{
    free(j->buf);
    j->buf = NULL;
}

static void put(struct json *j, const char *fmt, ...)
{
    va_list ap;
    for (;;) {
        size_t room = j->cap - j->len;
        va_start(ap, fmt);
        int n = j->buf ? vsnprintf(j->buf + j->len, room, fmt, ap) : -1;
        va_end(ap);
        if (n >= 0 && (size_t)n < room) {
            j->len += (size_t)n;
            return;
        }
        size_t cap = j->cap ? j->cap * 2 : 1024;
        if (n >= 0 && cap < j->len + (size_t)n + 1)
            cap = j->len + (size_t)n + 1;
        char *b = realloc(j->buf, cap);
        if (!b) {
            j->oom = 1;
            return;
        }
        j->buf = b;
        j->cap = cap;
    }
}

/* Characters JSON allows raw but YAML, whose parser reads sidecars back (libyaml), refuses (DEL,
   the C1 controls, U+FFFE and U+FFFF) or takes for line breaks, folded with the spaces around
   them (U+0085, U+2028, U+2029). */
static int yaml_unsafe(unsigned cp)
{
    return cp == 0x7f || (cp >= 0x80 && cp <= 0x9f) || cp == 0x2028 || cp == 0x2029 || cp == 0xfffe ||
           cp == 0xffff;
}

/* A JSON string: quotes, backslashes, control characters and yaml_unsafe ones escaped; a byte that
   is not part of well-formed UTF-8 (a file name in another encoding) becomes U+FFFD, as JSON text
   must be UTF-8. */
static void put_string(struct json *j, const char *s)
{
    put(j, "\"");
    for (const unsigned char *c = (const unsigned char *)s; *c;) {
        int n = sbuf_utf8_len((const char *)c);
        if (n == 0)
            put(j, "\\ufffd");
        else if (*c == '"' || *c == '\\')
            put(j, "\\%c", *c);
        else if (*c < 0x20 || yaml_unsafe(sbuf_code_point((const char *)c, n)))
            put(j, "\\u%04x", sbuf_code_point((const char *)c, n));
        else
            put(j, "%.*s", n, (const char *)c);
        c += n ? n : 1;
    }
    put(j, "\"");
}

static void member(struct json *j, const char *key)
{
    if (j->depth > 0) {
        put(j, j->first[j->depth] ? "\n" : ",\n");
        for (int i = 0; i < j->depth; i++)
            put(j, "  ");
    }
    j->first[j->depth] = 0;
    if (key) {
        put_string(j, key);
        put(j, ": ");
    }
}

static void open_(struct json *j, const char *key, const char *c)
{
    member(j, key);
    put(j, "%s", c);
    if (j->depth < 31)
        j->depth++;
    j->first[j->depth] = 1;
}

static void close_(struct json *j, const char *c)
{
    int empty = j->first[j->depth];
    if (j->depth > 0)
        j->depth--;
    if (!empty) {
        put(j, "\n");
        for (int i = 0; i < j->depth; i++)
            put(j, "  ");
    }
    put(j, "%s", c);
    if (j->depth == 0)
        put(j, "\n");
}

void json_begin_object(struct json *j, const char *key)
{
    open_(j, key, "{");
}
void json_end_object(struct json *j)
{
    close_(j, "}");
}
void json_begin_array(struct json *j, const char *key)
{
    open_(j, key, "[");
}
void json_end_array(struct json *j)
{
    close_(j, "]");
}

void json_string(struct json *j, const char *key, const char *val)
{
    member(j, key);
    put_string(j, val);
}

void json_number(struct json *j, const char *key, double val)
{
    member(j, key);
    if (isfinite(val))
        put(j, "%.10g", val);
    else
        put(j, "null");
}

void json_number_text(struct json *j, const char *key, const char *text)
{
    member(j, key);
    put(j, "%s", text);
}

void json_uint(struct json *j, const char *key, uint64_t val)
{
    member(j, key);
    put(j, "%llu", (unsigned long long)val);
}

void json_bool(struct json *j, const char *key, int val)
{
    member(j, key);
    put(j, "%s", val ? "true" : "false");
}

int json_string_read_back(const char *s, char *out, size_t n)
{
    size_t k = 0;
    for (const unsigned char *c = (const unsigned char *)s; *c;) {
        int len = sbuf_utf8_len((const char *)c);
        const char *piece = len ? (const char *)c : "\xef\xbf\xbd";
        size_t pl = len ? (size_t)len : 3;
        if (k + pl >= n)
            return -1;
        memcpy(out + k, piece, pl);
        k += pl;
        c += len ? len : 1;
    }
    if (n == 0)
        return -1;
    out[k] = 0;
    return 0;
}
