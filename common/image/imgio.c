/* imgio: reading PNG or PPM files by their magic bytes, writing them atomically. */
#include "imgio.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/fileio.h"
#include "png.h"
#include "ppm.h"

/* The formats we write, by name; a new one is a line here (and its encoder in imgio_write). */
static const struct {
    const char *name;
    enum img_format fmt;
} formats[] = {
    {"png", IMG_PNG},
    {"ppm", IMG_PPM},
};
enum { N_FORMATS = sizeof formats / sizeof formats[0] };

const char *img_format_name(enum img_format fmt)
{
    for (int i = 0; i < N_FORMATS; i++)
        if (formats[i].fmt == fmt)
            return formats[i].name;
    return "?";
}

int img_format_parse(const char *name, enum img_format *out)
{
    for (int i = 0; i < N_FORMATS; i++)
        if (!strcmp(formats[i].name, name)) {
            *out = formats[i].fmt;
            return 0;
        }
    return -1;
}

int img_format_of_file(const char *file, enum img_format *out)
{
    const char *dot = strrchr(file, '.');
    if (!dot)
        return 0;
    for (int i = 0; i < N_FORMATS; i++)
        if (!strcasecmp(formats[i].name, dot + 1)) {
            *out = formats[i].fmt;
            return 1;
        }
    return -1;
}

void img_format_list(char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = 0;
    for (int i = 0; i < N_FORMATS && used < n; i++)
        used += (size_t)snprintf(buf + used, n - used, "%s%s",
                                 i == 0               ? ""
                                 : i == N_FORMATS - 1 ? " or "
                                                      : ", ",
                                 formats[i].name);
}

/* Read a PNG or PPM file, chosen by its first bytes, into out (limit 512 MiB). 0 or -1. */
int imgio_read(const char *path, struct rgb8 *out, struct err *e)
{
    uint8_t *data;
    size_t len;
    out->w = 0;
    out->h = 0;
    out->px = NULL;
    if (fileio_read_all(path, IMGIO_MAX_BYTES, &data, &len, e) < 0)
        return -1;
    int rc;
    if (len >= 4 && memcmp(data, "\x89PNG", 4) == 0)
        rc = png_decode(data, len, path, out, e);
    else if (len >= 2 && data[0] == 'P' && data[1] >= '1' && data[1] <= '7')
        rc = ppm_decode(data, len, path, out, e); /* it names the netpbm variants it rejects */
    else
        rc = err_set(e, path, 0, 0, "unknown image format (expected PNG or PPM)");
    free(data);
    return rc;
}

/* Encode img as fmt and write it atomically to path. 0, or -1 with e filled. */
int imgio_write(const char *path, const struct rgb8 *img, enum img_format fmt, struct err *e)
{
    uint8_t *buf;
    size_t len;
    int rc = fmt == IMG_PNG ? png_encode(img, &buf, &len, e) : ppm_encode(img, &buf, &len, e);
    if (rc < 0) {
        if (e && !e->file[0])
            snprintf(e->file, sizeof e->file, "%s", path);
        return -1;
    }
    rc = fileio_write_atomic(path, buf, len, e);
    free(buf);
    return rc;
}
