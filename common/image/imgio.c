/* imgio: reading image files by their magic bytes (8-bit or float), writing them atomically. */
#include "imgio.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/fileio.h"
#include "exr.h"
#include "pfm.h"
#include "png.h"
#include "ppm.h"

/* The formats we write, by name; a new one is a line here (and its encoder in imgio_write or,
   for floats, imgio_write_f). */
static const struct {
    const char *name;
    enum img_format fmt;
} formats[] = {
    {"png", IMG_PNG},
    {"ppm", IMG_PPM},
    {"exr", IMG_EXR},
    {"pfm", IMG_PFM},
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

int imgio_read(const char *path, struct rgb8 *out, struct err *e)
{
    uint8_t *data;
    size_t len;
    *out = (struct rgb8){0};
    if (fileio_read_all(path, IMGIO_MAX_BYTES, &data, &len, e) < 0)
        return -1;
    int rc = imgio_decode(data, len, path, out, e);
    free(data);
    return rc;
}

int imgio_decode(const uint8_t *data, size_t len, const char *name, struct rgb8 *out, struct err *e)
{
    *out = (struct rgb8){0};
    if (len >= 4 && memcmp(data, "\x89PNG", 4) == 0)
        return png_decode(data, len, name, out, e);
    if (len >= 2 && data[0] == 'P' && data[1] >= '1' && data[1] <= '7')
        return ppm_decode(data, len, name, out, e); /* it names the netpbm variants it rejects */
    return err_set(e, name, 0, 0, "unknown image format (expected PNG or PPM)");
}

int imgio_size(const uint8_t *data, size_t len, const char *name, int *w, int *h, struct err *e)
{
    if (len >= 4 && memcmp(data, "\x89PNG", 4) == 0)
        return png_size(data, len, name, w, h, e);
    if (len >= 2 && data[0] == 'P' && data[1] >= '1' && data[1] <= '7')
        return ppm_size(data, len, name, w, h, e);
    return err_set(e, name, 0, 0, "unknown image format (expected PNG or PPM)");
}

int imgio_read_f(const char *path, struct rgbf *out, enum img_domain *domain, struct err *e)
{
    uint8_t *data;
    size_t len;
    *out = (struct rgbf){0};
    if (domain)
        *domain = IMG_LINEAR;
    if (fileio_read_all(path, EXR_MAX_BYTES, &data, &len, e) < 0)
        return -1;
    int rc = imgio_decode_f(data, len, path, out, domain, e);
    free(data);
    return rc;
}

int imgio_decode_f(const uint8_t *data, size_t len, const char *name, struct rgbf *out,
                   enum img_domain *domain, struct err *e)
{
    *out = (struct rgbf){0};
    if (domain)
        *domain = IMG_LINEAR;
    if (len >= 4 && memcmp(data, "\x76\x2f\x31\x01", 4) == 0) /* EXR's magic number */
        return exr_image_decode(data, len, name, out, e);
    if (len >= 3 && data[0] == 'P' && (data[1] == 'F' || data[1] == 'f') &&
        (data[2] == '\n' || data[2] == ' ' || data[2] == '\r' || data[2] == '\t')) /* "PF" or "Pf", a space */
        return pfm_decode(data, len, name, out, e);
    if (!(len >= 4 &&
          (memcmp(data, "\x89PNG", 4) == 0 || (data[0] == 'P' && data[1] >= '1' && data[1] <= '7'))))
        return err_set(e, name, 0, 0, "unknown image format (expected EXR, PFM, PNG or PPM)");
    struct rgb8 img = {0};
    int rc = data[0] == 0x89 ? png_decode(data, len, name, &img, e) : ppm_decode(data, len, name, &img, e);
    if (rc == 0)
        rc = image_f_from_rgb8(&img, out, e);
    image_free(&img);
    if (domain)
        *domain = IMG_DISPLAY8;
    return rc;
}

int imgio_is_float(enum img_format fmt)
{
    return fmt == IMG_EXR || fmt == IMG_PFM;
}

int imgio_encode_f(const struct rgbf *img, enum img_format fmt, const struct img_attr *attrs, size_t nattrs,
                   uint8_t **buf, size_t *len, struct err *e)
{
    return fmt == IMG_EXR   ? exr_image_encode(img, attrs, nattrs, buf, len, e)
           : fmt == IMG_PFM ? pfm_encode(img, buf, len, e)
                            : err_set(e, NULL, 0, 0, "not a float image format");
}

int imgio_encode(const struct rgb8 *img, enum img_format fmt, uint8_t **buf, size_t *len, struct err *e)
{
    return fmt == IMG_PNG ? png_encode(img, buf, len, e)
           : fmt == IMG_PPM
               ? ppm_encode(img, buf, len, e)
               : err_set(e, NULL, 0, 0, "%s holds floats: write it with imgio_write_f", img_format_name(fmt));
}

/* The encoded bytes buf (rc 0; freed here) written atomically to path; an encoding failure (rc
   -1) names path when e names no file. */
static int write_encoded(const char *path, int rc, uint8_t *buf, size_t len, struct err *e)
{
    if (rc < 0) {
        if (e && !e->file[0])
            snprintf(e->file, sizeof e->file, "%s", path);
        return -1;
    }
    rc = fileio_write_atomic(path, buf, len, e);
    free(buf);
    return rc;
}

int imgio_write_f(const char *path, const struct rgbf *img, enum img_format fmt, const struct img_attr *attrs,
                  size_t nattrs, struct err *e)
{
    uint8_t *buf = NULL;
    size_t len = 0;
    int rc = imgio_encode_f(img, fmt, attrs, nattrs, &buf, &len, e);
    return write_encoded(path, rc, buf, len, e);
}

int imgio_write(const char *path, const struct rgb8 *img, enum img_format fmt, struct err *e)
{
    uint8_t *buf = NULL;
    size_t len = 0;
    int rc = imgio_encode(img, fmt, &buf, &len, e);
    return write_encoded(path, rc, buf, len, e);
}
