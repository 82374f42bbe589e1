/* ppm: writing binary P6 and reading P3/P6 netpbm images (maxval up to 65535) in memory. */
#include "ppm.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PPM_MAXVAL_MAX 65535UL

/* A read position in the file, with the line and column for messages. */
struct ppm_cur {
    const uint8_t *p;
    size_t len, pos;
    int line;
    size_t line_start;
    const char *name;
    struct err *e;
};

/* Fill e at the cursor's line and column. Always returns -1. */
__attribute__((format(printf, 2, 3))) static int ppm_fail(const struct ppm_cur *c, const char *fmt, ...)
{
    char msg[sizeof c->e->msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return err_set(c->e, c->name, c->line, (int)(c->pos - c->line_start) + 1, "%s", msg);
}

/* Skip whitespace and '#' comments (to the end of the line), counting lines. */
static void skip_space(struct ppm_cur *c)
{
    while (c->pos < c->len) {
        int ch = c->p[c->pos];
        if (ch == '#') {
            while (c->pos < c->len && c->p[c->pos] != '\n' && c->p[c->pos] != '\r')
                c->pos++;
            continue;
        }
        if (!isspace(ch))
            return;
        c->pos++;
        if (ch == '\n') {
            c->line++;
            c->line_start = c->pos;
        }
    }
}

/* Read a decimal number no larger than limit, which must end at whitespace, '#' or the end. */
static int read_uint(struct ppm_cur *c, unsigned long limit, const char *what, unsigned long *out)
{
    skip_space(c);
    if (c->pos >= c->len)
        return ppm_fail(c, "truncated PPM: missing %s", what);
    if (!isdigit(c->p[c->pos]))
        return ppm_fail(c, "corrupt PPM: expected %s, got a non-digit", what);
    unsigned long v = 0;
    while (c->pos < c->len && isdigit(c->p[c->pos])) {
        /* limit <= 65535, so stopping as soon as v passes it keeps v * 10 from overflowing */
        v = v * 10 + (unsigned long)(c->p[c->pos] - '0');
        if (v > limit)
            return ppm_fail(c, "corrupt PPM: %s larger than %lu", what, limit);
        c->pos++;
    }
    if (c->pos < c->len && !isspace(c->p[c->pos]) && c->p[c->pos] != '#')
        return ppm_fail(c, "corrupt PPM: unexpected character after %s", what);
    *out = v;
    return 0;
}

/* Scale a sample from 0..maxval to 0..255, rounding to nearest. */
static uint8_t scale(unsigned long v, unsigned long maxval)
{
    return (uint8_t)((v * 255 + maxval / 2) / maxval);
}

/* P3 body: w*h*3 decimal samples, each at most maxval. */
static int read_plain(struct ppm_cur *c, unsigned long maxval, struct rgb8 *out)
{
    size_t n = (size_t)out->w * (size_t)out->h * 3;
    for (size_t i = 0; i < n; i++) {
        unsigned long v;
        if (read_uint(c, maxval, "sample", &v) < 0)
            return -1;
        out->px[i] = scale(v, maxval);
    }
    return 0;
}

/* P6 body: after one whitespace byte, w*h*3 samples of 1 byte (maxval < 256) or 2 big-endian. */
static int read_raw(struct ppm_cur *c, unsigned long maxval, struct rgb8 *out)
{
    if (c->pos >= c->len)
        return ppm_fail(c, "truncated PPM: no pixel data");
    if (!isspace(c->p[c->pos]))
        return ppm_fail(c, "corrupt PPM: expected one whitespace byte after maxval");
    c->pos++;
    size_t bytes = maxval > 255 ? 2 : 1;
    size_t n = (size_t)out->w * (size_t)out->h * 3;
    size_t left = c->len - c->pos;
    if (left / bytes < n)
        return err_set(c->e, c->name, 0, 0, "truncated PPM: pixel data is %zu bytes, expected %zu", left,
                       n * bytes);
    const uint8_t *s = c->p + c->pos;
    for (size_t i = 0; i < n; i++, s += bytes) {
        unsigned long v = bytes == 2 ? (unsigned long)s[0] << 8 | s[1] : s[0];
        if (v > maxval) {
            size_t px = i / 3;
            return err_set(c->e, c->name, 0, 0,
                           "corrupt PPM: sample %lu exceeds maxval %lu at pixel (%zu, %zu)", v, maxval,
                           px % (size_t)out->w, px / (size_t)out->w);
        }
        out->px[i] = scale(v, maxval);
    }
    return 0;
}

/* Check the magic: P3 or P6 followed by whitespace or a comment. */
static int read_magic(struct ppm_cur *c, int *plain)
{
    const uint8_t *p = c->p;
    if (c->len < 2 || p[0] != 'P' || p[1] < '1' || p[1] > '7')
        return ppm_fail(c, "not a PPM file (expected P3 or P6)");
    if (p[1] != '3' && p[1] != '6')
        return ppm_fail(c, "unsupported netpbm format P%c (only P3 and P6)", p[1]);
    c->pos = 2;
    if (c->len > 2 && !isspace(p[2]) && p[2] != '#')
        return ppm_fail(c, "corrupt PPM: bad magic number");
    *plain = p[1] == '3';
    return 0;
}

/* The magic, width and height of the header at c (checked as ppm_decode checks them). 0 or -1. */
static int read_size(struct ppm_cur *c, int *plain, unsigned long *w, unsigned long *h)
{
    if (read_magic(c, plain) < 0 || read_uint(c, IMAGE_MAX_SIDE, "width", w) < 0)
        return -1;
    if (*w < 1)
        return ppm_fail(c, "corrupt PPM: width must be at least 1");
    if (read_uint(c, IMAGE_MAX_SIDE, "height", h) < 0)
        return -1;
    if (*h < 1)
        return ppm_fail(c, "corrupt PPM: height must be at least 1");
    if (*w * *h > (unsigned long)IMAGE_MAX_PIXELS)
        return ppm_fail(c, "unsupported PPM: %lux%lu is over %ld pixels", *w, *h, IMAGE_MAX_PIXELS);
    return 0;
}

int ppm_size(const uint8_t *data, size_t len, const char *name, int *w, int *h, struct err *e)
{
    struct ppm_cur c = {data, len, 0, 1, 0, name, e};
    unsigned long uw, uh;
    int plain;
    if (read_size(&c, &plain, &uw, &uh) < 0)
        return -1;
    *w = (int)uw;
    *h = (int)uh;
    return 0;
}

int ppm_decode(const uint8_t *data, size_t len, const char *name, struct rgb8 *out, struct err *e)
{
    struct ppm_cur c = {data, len, 0, 1, 0, name, e};
    unsigned long w, h, maxval;
    int plain = 0;
    *out = (struct rgb8){0};
    if (read_size(&c, &plain, &w, &h) < 0 || read_uint(&c, PPM_MAXVAL_MAX, "maxval", &maxval) < 0)
        return -1;
    if (maxval < 1)
        return ppm_fail(&c, "corrupt PPM: maxval must be 1..65535");
    if (image_alloc(out, (int)w, (int)h, e) < 0)
        return err_set(e, name, 0, 0, "out of memory for a %lux%lu PPM", w, h);
    if ((plain ? read_plain(&c, maxval, out) : read_raw(&c, maxval, out)) < 0) {
        image_free(out);
        return -1;
    }
    return 0;
}

int ppm_encode(const struct rgb8 *img, uint8_t **out, size_t *out_len, struct err *e)
{
    *out = NULL;
    *out_len = 0;
    if (!img->px || img->w < 1 || img->h < 1 || img->w > IMAGE_MAX_SIDE || img->h > IMAGE_MAX_SIDE)
        return err_set(e, NULL, 0, 0, "cannot encode PPM: bad image %dx%d", img->w, img->h);
    char header[64];
    int hn = snprintf(header, sizeof header, "P6\n%d %d\n255\n", img->w, img->h);
    size_t n = (size_t)img->w * (size_t)img->h * 3;
    uint8_t *buf = malloc((size_t)hn + n);
    if (!buf)
        return err_set(e, NULL, 0, 0, "out of memory encoding PPM");
    memcpy(buf, header, (size_t)hn);
    memcpy(buf + hn, img->px, n);
    *out = buf;
    *out_len = (size_t)hn + n;
    return 0;
}
