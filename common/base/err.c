/* err: filling and formatting the error struct that library calls return. */
#include "err.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int err_set(struct err *e, const char *file, int line, int col, const char *fmt, ...)
{
    if (!e)
        return -1;
    snprintf(e->file, sizeof e->file, "%s", file ? file : "");
    e->line = line;
    e->col = col;
    e->errnum = 0;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->msg, sizeof e->msg, fmt, ap);
    va_end(ap);
    return -1;
}

int err_set_errno(struct err *e, int errnum, const char *fmt, ...)
{
    if (!e)
        return -1;
    e->file[0] = 0;
    e->line = e->col = 0;
    e->errnum = errnum;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->msg, sizeof e->msg, fmt, ap);
    va_end(ap);
    return -1;
}

int err_prefix(struct err *e, const char *prefix)
{
    if (!e)
        return -1;
    char tmp[sizeof e->msg];
    snprintf(tmp, sizeof tmp, "%s: %s", prefix, e->msg);
    memcpy(e->msg, tmp, sizeof tmp);
    return -1;
}

/* Copy s to out (n bytes, NUL-terminated) with control characters escaped (\n, \t, \r, \xHH): a
   value quoted in a message may hold a newline, and an error must stay one line. */
static void escape_controls(const char *s, char *out, size_t n)
{
    size_t k = 0;
    for (; *s && k + 5 < n; s++) {
        unsigned char c = (unsigned char)*s;
        if (c >= 0x20 && c != 0x7f)
            out[k++] = (char)c;
        else if (c == '\n' || c == '\t' || c == '\r')
            k += (size_t)snprintf(out + k, n - k, "\\%c", c == '\n' ? 'n' : c == '\t' ? 't' : 'r');
        else
            k += (size_t)snprintf(out + k, n - k, "\\x%02x", c);
    }
    out[k] = 0;
}

void err_format(const struct err *e, char *buf, size_t n)
{
    char file[sizeof e->file * 4], msg[sizeof e->msg * 4];
    escape_controls(e->file, file, sizeof file);
    escape_controls(e->msg, msg, sizeof msg);
    if (e->file[0] && e->line > 0)
        snprintf(buf, n, "%s:%d:%d: %s", file, e->line, e->col > 0 ? e->col : 1, msg);
    else if (e->file[0])
        snprintf(buf, n, "%s: %s", file, msg);
    else
        snprintf(buf, n, "%s", msg);
}

void err_print(const char *fmt, ...)
{
    struct err e = {.file = "", .line = 0, .col = 0};
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e.msg, sizeof e.msg, fmt, ap);
    va_end(ap);
    size_t n = strlen(e.msg);
    if (n > 0 && e.msg[n - 1] == '\n')
        e.msg[n - 1] = 0;
    char line[sizeof e.msg * 4 + 16];
    err_format(&e, line, sizeof line);
    fprintf(stderr, "%s\n", line);
}
