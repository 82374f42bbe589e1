/* json: writing JSON text with escaping and pretty two-space indentation. */
#include "json.h"
#include "sbuf.h"

#include <math.h>
#include <string.h>

void json_init(struct json *j)
{
    memset(j, 0, sizeof *j);
    j->first[0] = 1;
}

void json_free(struct json *j)
{
    sbuf_free(&j->text);
}

static void add(struct json *j, const char *s)
{
    sbuf_put(&j->text, s, strlen(s));
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
    add(j, "\"");
    for (const unsigned char *c = (const unsigned char *)s; *c;) {
        int n = sbuf_utf8_len((const char *)c);
        if (n == 0)
            add(j, "\\ufffd");
        else if (*c == '"' || *c == '\\')
            sbuf_printf(&j->text, "\\%c", *c);
        else if (*c < 0x20 || yaml_unsafe(sbuf_code_point((const char *)c, n)))
            sbuf_printf(&j->text, "\\u%04x", sbuf_code_point((const char *)c, n));
        else
            sbuf_put(&j->text, (const char *)c, (size_t)n);
        c += n ? n : 1;
    }
    add(j, "\"");
}

static void member(struct json *j, const char *key)
{
    if (j->depth > 0) {
        add(j, j->first[j->depth] ? "\n" : ",\n");
        for (int i = 0; i < j->depth; i++)
            add(j, "  ");
    }
    j->first[j->depth] = 0;
    if (key) {
        put_string(j, key);
        add(j, ": ");
    }
}

static void open_(struct json *j, const char *key, const char *c)
{
    member(j, key);
    add(j, c);
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
        add(j, "\n");
        for (int i = 0; i < j->depth; i++)
            add(j, "  ");
    }
    add(j, c);
    if (j->depth == 0)
        add(j, "\n");
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
        sbuf_printf(&j->text, "%.10g", val);
    else
        add(j, "null");
}

void json_number_text(struct json *j, const char *key, const char *text)
{
    member(j, key);
    add(j, text);
}

void json_uint(struct json *j, const char *key, uint64_t val)
{
    member(j, key);
    sbuf_printf(&j->text, "%llu", (unsigned long long)val);
}

void json_bool(struct json *j, const char *key, int val)
{
    member(j, key);
    add(j, val ? "true" : "false");
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
