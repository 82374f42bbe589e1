/* err: filling and formatting the error struct that library calls return. */
#include "err.h"
#include "sbuf.h"

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

void err_format(const struct err *e, char *buf, size_t n)
{
    char file[sizeof e->file * 4], msg[sizeof e->msg * 4];
    sbuf_show(e->file, file, sizeof file); /* an error stays one line, safe to show */
    sbuf_show(e->msg, msg, sizeof msg);
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
