/* png_decode: a bounds-checked decoder of any PNG (every colour type and bit depth, Adam7) into
   8-bit RGB; the encoder is png.c. */
#include "png.h"
#include "png_internal.h"

#include <stdlib.h>
#include <string.h>

#define ZLIB_CONST
#include <zlib.h>

/* Decoder state, from IHDR to IEND. */
struct png_dec {
    const char *name;
    struct err *e;
    uint32_t w, h;
    int color_type, channels, depth, interlace;
    int bits;      /* bits per pixel: channels * depth */
    int palette_n; /* PLTE entries (0: none seen) */
    uint8_t palette[768];
    uint8_t *raw; /* each pass's rows of (filter byte, packed pixels), inflated */
    size_t raw_len;
    z_stream zs;
    int zs_open, z_done, seen_idat;
};

/* Adam7 (PNG spec 8.2): each pass's first column and row and its steps; pass 0 alone when not
   interlaced, with steps of 1. */
static const uint8_t adam7_x0[7] = {0, 4, 0, 2, 0, 1, 0}, adam7_y0[7] = {0, 0, 4, 0, 2, 0, 1};
static const uint8_t adam7_dx[7] = {8, 8, 4, 4, 2, 2, 1}, adam7_dy[7] = {8, 8, 8, 4, 4, 2, 2};

struct png_pass {
    uint32_t x0, y0, dx, dy, w, h; /* w or h 0: the pass is empty and has no rows at all */
    size_t stride;                 /* bytes of packed pixels per row, without the filter byte */
};

static struct png_pass pass_of(const struct png_dec *d, int i)
{
    struct png_pass p = {0, 0, 1, 1, d->w, d->h, 0};
    if (d->interlace) {
        p.x0 = adam7_x0[i];
        p.y0 = adam7_y0[i];
        p.dx = adam7_dx[i];
        p.dy = adam7_dy[i];
        p.w = d->w > p.x0 ? (d->w - p.x0 + p.dx - 1) / p.dx : 0;
        p.h = d->h > p.y0 ? (d->h - p.y0 + p.dy - 1) / p.dy : 0;
    }
    p.stride = ((size_t)p.w * (size_t)d->bits + 7) / 8;
    if (!p.w || !p.h)
        p.w = p.h = 0;
    return p;
}

struct png_chunk {
    char type[5];
    const uint8_t *data;
    uint32_t len;
};

static int is_type(const struct png_chunk *c, const char *t)
{
    return memcmp(c->type, t, 4) == 0;
}

/* Read the chunk at *pos into c and advance; every length is checked against len. */
static int next_chunk(struct png_dec *d, const uint8_t *data, size_t len, size_t *pos, struct png_chunk *c)
{
    size_t left = len - *pos;
    if (left == 0)
        return err_set(d->e, d->name, 0, 0, "truncated PNG: missing IEND chunk");
    if (left < 12)
        return err_set(d->e, d->name, 0, 0, "truncated PNG: incomplete chunk at offset %zu", *pos);
    const uint8_t *p = data + *pos;
    for (int i = 0; i < 4; i++) {
        int ch = p[4 + i];
        if (!((ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z')))
            return err_set(d->e, d->name, 0, 0, "corrupt PNG: bad chunk type at offset %zu", *pos);
        c->type[i] = (char)ch;
    }
    c->type[4] = '\0';
    c->len = get_be32(p);
    if (c->len > PNG_CHUNK_MAX)
        return err_set(d->e, d->name, 0, 0, "corrupt PNG: chunk %s has length %lu", c->type,
                       (unsigned long)c->len);
    if (c->len > left - 12)
        return err_set(d->e, d->name, 0, 0, "truncated PNG: chunk %s runs past end of file", c->type);
    c->data = p + 8;
    uLong crc = crc32(0L, p + 4, 4 + c->len);
    if ((uint32_t)crc != get_be32(p + 8 + c->len))
        return err_set(d->e, d->name, 0, 0, "corrupt PNG: CRC mismatch in chunk %s", c->type);
    *pos += 12 + (size_t)c->len;
    return 0;
}

/* Channels per pixel for a colour type (a palette index is one), or 0 for an unknown type. */
static int channels_of(int color_type)
{
    static const int channels[7] = {1, 0, 3, 1, 2, 0, 4}; /* gray, -, RGB, palette, gray + alpha, -, RGBA */
    return color_type >= 0 && color_type < 7 ? channels[color_type] : 0;
}

/* Whether the spec (table 11.1) allows this bit depth for this colour type. */
static int depth_allowed(int color_type, int depth)
{
    if (color_type == 0)
        return depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
    if (color_type == 3)
        return depth == 1 || depth == 2 || depth == 4 || depth == 8;
    return depth == 8 || depth == 16;
}

/* Check IHDR, then allocate the inflate buffer for exactly the declared image. */
static int parse_ihdr(struct png_dec *d, const struct png_chunk *c)
{
    if (c->len != 13)
        return err_set(d->e, d->name, 0, 0, "corrupt PNG: IHDR has length %lu, expected 13",
                       (unsigned long)c->len);
    const uint8_t *p = c->data;
    uint32_t w = get_be32(p), h = get_be32(p + 4);
    int depth = p[8], ct = p[9];
    if (w < 1 || h < 1 || w > IMAGE_MAX_SIDE || h > IMAGE_MAX_SIDE)
        return err_set(d->e, d->name, 0, 0, "unsupported PNG: size %lux%lu (sides must be 1..%d)",
                       (unsigned long)w, (unsigned long)h, IMAGE_MAX_SIDE);
    if ((uint64_t)w * h > (uint64_t)IMAGE_MAX_PIXELS)
        return err_set(d->e, d->name, 0, 0, "unsupported PNG: %lux%lu is over %ld pixels", (unsigned long)w,
                       (unsigned long)h, IMAGE_MAX_PIXELS);
    if (!channels_of(ct))
        return err_set(d->e, d->name, 0, 0, "corrupt PNG: bad color type %d", ct);
    if (!depth_allowed(ct, depth))
        return err_set(d->e, d->name, 0, 0, "corrupt PNG: bit depth %d is not allowed for color type %d",
                       depth, ct);
    if (p[10] != 0 || p[11] != 0)
        return err_set(d->e, d->name, 0, 0, "corrupt PNG: unknown compression or filter method");
    if (p[12] > 1)
        return err_set(d->e, d->name, 0, 0, "corrupt PNG: bad interlace method %d", p[12]);
    d->w = w;
    d->h = h;
    d->color_type = ct;
    d->channels = channels_of(ct);
    d->depth = depth;
    d->interlace = p[12];
    d->bits = d->channels * depth;
    d->raw_len = 0; /* at most 8 bytes a pixel plus the filter bytes: < 2^32 by the limits */
    for (int i = 0; i < (d->interlace ? 7 : 1); i++) {
        struct png_pass ps = pass_of(d, i);
        d->raw_len += (size_t)ps.h * (ps.stride + 1);
    }
    d->raw = malloc(d->raw_len);
    if (!d->raw)
        return err_set(d->e, d->name, 0, 0, "out of memory for a %lux%lu PNG", (unsigned long)w,
                       (unsigned long)h);
    if (inflateInit(&d->zs) != Z_OK)
        return err_set(d->e, d->name, 0, 0, "out of memory starting zlib");
    d->zs_open = 1;
    d->zs.next_out = d->raw;
    d->zs.avail_out = (uInt)d->raw_len;
    return 0;
}

/* Inflate one IDAT's bytes into raw; output beyond the declared image size is an error. */
static int feed_idat(struct png_dec *d, const struct png_chunk *c)
{
    d->seen_idat = 1;
    if (d->z_done)
        return 0; /* bytes after the end of the zlib stream are ignored, as libpng does */
    d->zs.next_in = c->data;
    d->zs.avail_in = c->len;
    while (d->zs.avail_in > 0) {
        int zr = inflate(&d->zs, Z_NO_FLUSH);
        if (zr == Z_STREAM_END) {
            d->z_done = 1;
            if (d->zs.total_out != d->raw_len)
                return err_set(d->e, d->name, 0, 0, "corrupt PNG: image data is %lu bytes, expected %zu",
                               (unsigned long)d->zs.total_out, d->raw_len);
            return 0;
        }
        /* With input left, no progress means the output buffer is full. */
        if (zr == Z_BUF_ERROR)
            return err_set(d->e, d->name, 0, 0,
                           "corrupt PNG: image data is larger than the expected %zu bytes", d->raw_len);
        if (zr != Z_OK)
            return err_set(d->e, d->name, 0, 0, "corrupt PNG: bad zlib data in IDAT (%s)",
                           d->zs.msg ? d->zs.msg : "unexpected zlib state");
    }
    return 0;
}

/* Undo the row filters in place, pass by pass (each pass starts from a row of zeros), checking
   each filter type. Filters work on whole bytes: a pixel of fewer than 8 bits steps by one. */
static int unfilter_image(struct png_dec *d)
{
    size_t step = d->bits >= 8 ? (size_t)d->bits / 8 : 1;
    uint8_t *zero = calloc(((size_t)d->w * (size_t)d->bits + 7) / 8 + 1, 1); /* a full-width row */
    if (!zero)
        return err_set(d->e, d->name, 0, 0, "out of memory decoding PNG");
    uint8_t *row = d->raw;
    for (int i = 0; i < (d->interlace ? 7 : 1); i++) {
        struct png_pass ps = pass_of(d, i);
        const uint8_t *prev = zero;
        for (uint32_t y = 0; y < ps.h; y++, row += ps.stride + 1) {
            if (row[0] > 4) {
                free(zero);
                return err_set(d->e, d->name, 0, 0, "corrupt PNG: bad filter type %d on row %lu%s", row[0],
                               (unsigned long)y, d->interlace ? " of an interlaced pass" : "");
            }
            unfilter_row(row[0], row + 1, prev, ps.stride, step);
            prev = row + 1;
        }
    }
    free(zero);
    return 0;
}

/* Sample i of a row of packed samples, scaled to 8 bits (palette indices are left as they are). */
static int sample8(const struct png_dec *d, const uint8_t *row, size_t i)
{
    switch (d->depth) {
    case 16:
        return ((row[2 * i] * 256 + row[2 * i + 1]) * 255 + 32767) / 65535; /* rounded */
    case 8:
        return row[i];
    default: { /* 1, 2 or 4 bits, the leftmost pixel in the high bits */
        size_t bit = i * (size_t)d->depth;
        int v = row[bit / 8] >> (8 - d->depth - (int)(bit % 8)) & ((1 << d->depth) - 1);
        return d->color_type == 3 ? v : v * 255 / ((1 << d->depth) - 1);
    }
    }
}

/* Convert the unfiltered rows to RGB in out: gray is replicated, palette indices looked up, alpha
   dropped, 16-bit samples cut to 8, each interlaced pass's pixels put in their places. */
static int to_rgb(const struct png_dec *d, struct rgb8 *out)
{
    if (d->color_type == 3 && !d->palette_n)
        return err_set(d->e, d->name, 0, 0, "corrupt PNG: palette image without a PLTE chunk");
    if (image_alloc(out, (int)d->w, (int)d->h, d->e) < 0)
        return err_set(d->e, d->name, 0, 0, "out of memory for a %lux%lu PNG", (unsigned long)d->w,
                       (unsigned long)d->h);
    const uint8_t *row = d->raw + 1;
    for (int i = 0; i < (d->interlace ? 7 : 1); i++) {
        struct png_pass ps = pass_of(d, i);
        for (uint32_t y = 0; y < ps.h; y++, row += ps.stride + 1) {
            for (uint32_t x = 0; x < ps.w; x++) {
                uint8_t *dst = out->px + ((size_t)(ps.y0 + y * ps.dy) * d->w + ps.x0 + x * ps.dx) * 3;
                size_t s0 = (size_t)x * (size_t)d->channels;
                int v = sample8(d, row, s0);
                if (d->color_type == 3) {
                    if (v >= d->palette_n) {
                        image_free(out);
                        return err_set(d->e, d->name, 0, 0, "corrupt PNG: palette index %d of %d entries", v,
                                       d->palette_n);
                    }
                    memcpy(dst, d->palette + 3 * v, 3);
                } else if (d->color_type == 0 || d->color_type == 4) {
                    dst[0] = dst[1] = dst[2] = (uint8_t)v;
                } else {
                    dst[0] = (uint8_t)v;
                    dst[1] = (uint8_t)sample8(d, row, s0 + 1);
                    dst[2] = (uint8_t)sample8(d, row, s0 + 2);
                }
            }
        }
    }
    return 0;
}

/* Walk the chunks after the signature up to IEND, inflating IDAT data as it comes. */
static int read_chunks(struct png_dec *d, const uint8_t *data, size_t len)
{
    size_t pos = sizeof png_signature;
    struct png_chunk c;
    for (;;) {
        if (next_chunk(d, data, len, &pos, &c) < 0)
            return -1;
        if (!d->raw && !is_type(&c, "IHDR"))
            return err_set(d->e, d->name, 0, 0, "corrupt PNG: first chunk is %s, expected IHDR", c.type);
        if (is_type(&c, "IHDR")) {
            if (d->raw)
                return err_set(d->e, d->name, 0, 0, "corrupt PNG: second IHDR chunk");
            if (parse_ihdr(d, &c) < 0)
                return -1;
        } else if (is_type(&c, "IDAT")) {
            if (feed_idat(d, &c) < 0)
                return -1;
        } else if (is_type(&c, "IEND")) {
            return 0;
        } else if (is_type(&c, "PLTE")) {
            /* a suggested palette is allowed for RGB and RGBA; gray images must not have one */
            if (d->color_type == 0 || d->color_type == 4)
                return err_set(d->e, d->name, 0, 0, "corrupt PNG: PLTE chunk in a gray image");
            if (d->color_type != 3)
                continue; /* only a suggestion for RGB and RGBA (libpng warns on a bad one) */
            if (d->seen_idat)
                return err_set(d->e, d->name, 0, 0, "corrupt PNG: PLTE chunk after the image data (IDAT)");
            if (d->palette_n)
                return err_set(d->e, d->name, 0, 0, "corrupt PNG: second PLTE chunk");
            if (c.len == 0 || c.len % 3 || c.len > sizeof d->palette)
                return err_set(d->e, d->name, 0, 0,
                               "corrupt PNG: PLTE chunk of %lu bytes (1 to 256 entries of 3 bytes)",
                               (unsigned long)c.len);
            memcpy(d->palette, c.data, c.len);
            d->palette_n = (int)(c.len / 3);
        } else if (!(c.type[0] & 0x20)) {
            return err_set(d->e, d->name, 0, 0, "unsupported PNG: unknown critical chunk %s", c.type);
        }
    }
}

int png_size(const uint8_t *data, size_t len, const char *name, int *w, int *h, struct err *e)
{
    struct png_dec d = {.name = name, .e = e};
    struct png_chunk c;
    size_t pos = sizeof png_signature;
    if (len < sizeof png_signature || memcmp(data, png_signature, sizeof png_signature) != 0)
        return err_set(e, name, 0, 0, "not a PNG file (bad signature)");
    if (next_chunk(&d, data, len, &pos, &c) < 0)
        return -1;
    if (!is_type(&c, "IHDR") || c.len != 13)
        return err_set(e, name, 0, 0, "corrupt PNG: first chunk is %s (%lu bytes), expected IHDR (13)",
                       c.type, (unsigned long)c.len);
    uint32_t pw = get_be32(c.data), ph = get_be32(c.data + 4);
    if (pw < 1 || ph < 1 || pw > IMAGE_MAX_SIDE || ph > IMAGE_MAX_SIDE)
        return err_set(e, name, 0, 0, "unsupported PNG: size %lux%lu (sides must be 1..%d)",
                       (unsigned long)pw, (unsigned long)ph, IMAGE_MAX_SIDE);
    *w = (int)pw;
    *h = (int)ph;
    return 0;
}

int png_decode(const uint8_t *data, size_t len, const char *name, struct rgb8 *out, struct err *e)
{
    struct png_dec d = {.name = name, .e = e};
    *out = (struct rgb8){0};
    int rc = -1;
    if (len < sizeof png_signature || memcmp(data, png_signature, sizeof png_signature) != 0)
        return err_set(e, name, 0, 0, "not a PNG file (bad signature)");
    if (read_chunks(&d, data, len) < 0)
        goto done;
    if (!d.seen_idat) {
        err_set(e, name, 0, 0, "corrupt PNG: no IDAT chunk");
        goto done;
    }
    if (!d.z_done) {
        err_set(e, name, 0, 0, "truncated PNG: image data ends after %lu of %zu bytes",
                (unsigned long)d.zs.total_out, d.raw_len);
        goto done;
    }
    if (unfilter_image(&d) < 0 || to_rgb(&d, out) < 0)
        goto done;
    rc = 0;
done:
    if (d.zs_open)
        inflateEnd(&d.zs);
    free(d.raw);
    return rc;
}
