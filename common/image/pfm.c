/* pfm: the Portable Float Map, a three-line text header ("PF", "W H", scale: negative for
   little-endian) and then raw 32-bit floats, the bottom row first. */
#include "pfm.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Whether this machine stores floats little-endian (GCC's and clang's predefined byte order). */
#define HOST_LITTLE_ENDIAN (__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__)

int pfm_encode(const struct rgbf *img, uint8_t **out, size_t *out_len, struct err *e)
{
    *out = NULL;
    *out_len = 0;
    if (!img->px || img->w < 1 || img->h < 1 || img->w > IMAGE_MAX_SIDE || img->h > IMAGE_MAX_SIDE)
        return err_set(e, NULL, 0, 0, "PFM: image size %dx%d out of range", img->w, img->h);
    char head[64];
    int hl = snprintf(head, sizeof head, "PF\n%d %d\n-1.0\n", img->w, img->h);
    size_t row = (size_t)img->w * 3 * 4, n = (size_t)hl + row * (size_t)img->h;
    uint8_t *buf = malloc(n);
    if (!buf)
        return err_set(e, NULL, 0, 0, "PFM: out of memory for a %dx%d image", img->w, img->h);
    memcpy(buf, head, (size_t)hl);
    int le = HOST_LITTLE_ENDIAN;
    for (int y = 0; y < img->h; y++) {
        const float *src = img->px + (size_t)(img->h - 1 - y) * img->w * 3; /* bottom row first */
        uint8_t *dst = buf + hl + row * (size_t)y;
        for (size_t i = 0; i < (size_t)img->w * 3; i++) {
            uint32_t u;
            memcpy(&u, &src[i], 4);
            if (!le)
                u = u >> 24 | (u >> 8 & 0xff00) | (u << 8 & 0xff0000) | u << 24;
            memcpy(dst + 4 * i, &u, 4);
        }
    }
    *out = buf;
    *out_len = n;
    return 0;
}

/* One header token (no leading whitespace allowed at *pos beyond what is skipped here) into tok. */
static int header_token(const uint8_t *d, size_t len, size_t *pos, char *tok, size_t n)
{
    while (*pos < len && (d[*pos] == ' ' || d[*pos] == '\t' || d[*pos] == '\n' || d[*pos] == '\r'))
        (*pos)++;
    size_t k = 0;
    while (*pos < len && d[*pos] != ' ' && d[*pos] != '\t' && d[*pos] != '\n' && d[*pos] != '\r') {
        if (k + 1 >= n)
            return -1;
        tok[k++] = (char)d[(*pos)++];
    }
    tok[k] = 0;
    return k ? 0 : -1;
}

/* A side: decimal digits only, 1..IMAGE_MAX_SIDE (too many digits: strtol's LONG_MAX, refused). */
static int parse_side(const char *t, int *out)
{
    if (!*t || t[strspn(t, "0123456789")])
        return -1;
    long v = strtol(t, NULL, 10);
    if (v < 1 || v > IMAGE_MAX_SIDE)
        return -1;
    *out = (int)v;
    return 0;
}

int pfm_decode(const uint8_t *data, size_t len, const char *name, struct rgbf *out, struct err *e)
{
    *out = (struct rgbf){0};
    char tok[32];
    size_t pos = 0;
    int w, h;
    if (len < 2 || data[0] != 'P' || (data[1] != 'F' && data[1] != 'f'))
        return err_set(e, name, 0, 0, "corrupt PFM: expected \"PF\" or \"Pf\"");
    int channels = data[1] == 'F' ? 3 : 1;
    pos = 2;
    if (header_token(data, len, &pos, tok, sizeof tok) < 0 || parse_side(tok, &w) < 0)
        return err_set(e, name, 0, 0, "corrupt PFM: width must be a number 1..%d", IMAGE_MAX_SIDE);
    if (header_token(data, len, &pos, tok, sizeof tok) < 0 || parse_side(tok, &h) < 0)
        return err_set(e, name, 0, 0, "corrupt PFM: height must be a number 1..%d", IMAGE_MAX_SIDE);
    if ((long)w * h > IMAGE_MAX_PIXELS)
        return err_set(e, name, 0, 0, "PFM: %dx%d is over the %ld-pixel limit", w, h, IMAGE_MAX_PIXELS);
    char *end;
    if (header_token(data, len, &pos, tok, sizeof tok) < 0)
        return err_set(e, name, 0, 0, "truncated PFM: missing the scale");
    double scale = strtod(tok, &end);
    if (*end || !isfinite(scale) || scale == 0)
        return err_set(e, name, 0, 0, "corrupt PFM: scale must be a non-zero number, got \"%s\"", tok);
    /* exactly one whitespace character ends the header, then the raster; or a CR LF (a header
       written with Windows line ends), when the raster's length says so */
    if (pos >= len || (data[pos] != '\n' && data[pos] != ' ' && data[pos] != '\r' && data[pos] != '\t'))
        return err_set(e, name, 0, 0, "truncated PFM: no raster after the header");
    size_t row = (size_t)w * (size_t)channels * 4, need = row * (size_t)h;
    pos += data[pos] == '\r' && len - pos >= 2 && data[pos + 1] == '\n' && len - pos - 2 == need ? 2 : 1;
    if (len - pos < need)
        return err_set(e, name, 0, 0, "truncated PFM: %zu bytes of raster, %dx%d needs %zu", len - pos, w, h,
                       need);
    if (len - pos > need)
        return err_set(e, name, 0, 0, "corrupt PFM: %zu bytes after the raster", len - pos - need);
    if (image_f_alloc(out, w, h, e) < 0)
        return -1;
    int swap = (scale < 0) != HOST_LITTLE_ENDIAN;
    for (int y = 0; y < h; y++) {
        const uint8_t *src = data + pos + row * (size_t)y;
        float *dst = out->px + (size_t)(h - 1 - y) * w * 3; /* the file's first row is the bottom */
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++) {
                uint32_t u;
                memcpy(&u, src + 4 * ((size_t)x * channels + (channels == 3 ? c : 0)), 4);
                if (swap)
                    u = u >> 24 | (u >> 8 & 0xff00) | (u << 8 & 0xff0000) | u << 24;
                memcpy(&dst[(size_t)x * 3 + c], &u, 4);
            }
    }
    /* the scale's magnitude multiplies the values, as pbrt reads a PFM */
    const float mag = (float)fabs(scale);
    for (size_t i = 0; mag != 1.0f && i < (size_t)w * h * 3; i++)
        out->px[i] *= mag;
    return 0;
}
