/* test_png: the PNG encoder and decoder, checked against PNGs built and read here with zlib
   alone (the PPM codec and the image buffer: test_ppm). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "check.h"
#include "image/image.h"
#include "image_fixture.h"
#include "image/png.h"

/* ---- a byte buffer and a hand-made PNG writer/reader, independent of png.c ---- */

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static void add_chunk(struct buf *b, const char *type, const uint8_t *data, size_t n)
{
    uint8_t len[4], crc[4];
    put32(len, (uint32_t)n);
    uLong c = crc32(0L, (const Bytef *)type, 4);
    if (n) /* crc32(c, NULL, 0) returns 0, not c */
        c = crc32(c, data, (uInt)n);
    put32(crc, (uint32_t)c);
    buf_add(b, len, 4);
    buf_add(b, type, 4);
    buf_add(b, data, n);
    buf_add(b, crc, 4);
}

static const uint8_t signature[8] = {137, 80, 78, 71, 13, 10, 26, 10};

static int ref_paeth(int a, int b, int c)
{
    int p = a + b - c, pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
    return (pa <= pb && pa <= pc) ? a : (pb <= pc ? b : c);
}

/* Predictor for byte i of a row; left/up/upleft are zero outside the image. */
static int ref_pred(int f, const uint8_t *row, const uint8_t *up, size_t i, int bpp)
{
    int a = i >= (size_t)bpp ? row[i - bpp] : 0;
    int b = up ? up[i] : 0;
    int c = (up && i >= (size_t)bpp) ? up[i - bpp] : 0;
    if (f == 1)
        return a;
    if (f == 2)
        return b;
    if (f == 3)
        return (a + b) >> 1;
    if (f == 4)
        return ref_paeth(a, b, c);
    return 0;
}

/* Filter samples (w*h*ch) into rows of (filter byte, bytes); mode < 0 cycles filters 0..4. */
static uint8_t *ref_filter(const uint8_t *s, int w, int h, int ch, int mode, size_t *raw_len)
{
    size_t stride = (size_t)w * ch;
    *raw_len = (size_t)h * (stride + 1);
    uint8_t *raw = malloc(*raw_len);
    for (int y = 0; y < h; y++) {
        int f = mode < 0 ? y % 5 : mode;
        const uint8_t *row = s + y * stride, *up = y ? row - stride : NULL;
        uint8_t *dst = raw + y * (stride + 1);
        dst[0] = (uint8_t)f;
        for (size_t i = 0; i < stride; i++)
            dst[1 + i] = (uint8_t)(row[i] - ref_pred(f, row, up, i, ch));
    }
    return raw;
}

/* A PNG with the given IHDR fields around raw (filtered rows), IDAT split every `split` bytes of
   zlib data (0: one IDAT), and an optional extra chunk before the first IDAT. */
static struct buf ref_png(uint32_t w, uint32_t h, int depth, int ct, int interlace, const uint8_t *raw,
                          size_t raw_len, size_t split, const char *extra)
{
    struct buf b = {0};
    uint8_t ihdr[13] = {0};
    put32(ihdr, w);
    put32(ihdr + 4, h);
    ihdr[8] = (uint8_t)depth;
    ihdr[9] = (uint8_t)ct;
    ihdr[12] = (uint8_t)interlace;
    buf_add(&b, signature, 8);
    add_chunk(&b, "IHDR", ihdr, 13);
    if (extra)
        add_chunk(&b, extra, (const uint8_t *)"hello", 5);
    uLongf zn = compressBound(raw_len);
    uint8_t *z = malloc(zn);
    compress2(z, &zn, raw, raw_len, 9);
    if (!split)
        split = zn;
    for (size_t off = 0; off < zn; off += split)
        add_chunk(&b, "IDAT", z + off, zn - off < split ? zn - off : split);
    add_chunk(&b, "IEND", NULL, 0);
    free(z);
    return b;
}

/* Independent reader for 8-bit RGB PNGs: chunks by hand, zlib uncompress, our own unfilter.
   Returns malloc'd w*h*3 pixels or NULL on anything unexpected. */
static uint8_t *ref_decode_rgb(const uint8_t *p, size_t n, int *w, int *h)
{
    if (n < 8 || memcmp(p, signature, 8) != 0)
        return NULL;
    struct buf z = {0};
    size_t pos = 8;
    int ok = 0;
    *w = *h = 0;
    while (pos + 12 <= n) {
        uint32_t len = get32(p + pos);
        if (len > n - pos - 12)
            break;
        const uint8_t *type = p + pos + 4, *data = p + pos + 8;
        if (crc32(crc32(0L, type, 4), data, len) != get32(data + len))
            break;
        if (!memcmp(type, "IHDR", 4) && len == 13 && data[8] == 8 && data[9] == 2 && !data[12]) {
            *w = (int)get32(data);
            *h = (int)get32(data + 4);
        } else if (!memcmp(type, "IDAT", 4)) {
            buf_add(&z, data, len);
        } else if (!memcmp(type, "IEND", 4)) {
            ok = pos + 12 == n;
            break;
        }
        pos += 12 + len;
    }
    if (!ok || *w < 1 || *h < 1) {
        free(z.p);
        return NULL;
    }
    size_t stride = (size_t)*w * 3;
    uLongf raw_len = (uLongf)(*h * (stride + 1)) + 1; /* one spare byte detects excess data */
    uint8_t *raw = malloc(raw_len), *px = malloc(stride * *h);
    int zr = uncompress(raw, &raw_len, z.p, z.n);
    free(z.p);
    if (zr != Z_OK || raw_len != *h * (stride + 1)) {
        free(raw);
        free(px);
        return NULL;
    }
    for (int y = 0; y < *h; y++) {
        int f = raw[y * (stride + 1)];
        const uint8_t *src = raw + y * (stride + 1) + 1;
        uint8_t *row = px + y * stride, *up = y ? row - stride : NULL;
        if (f > 4)
            ok = 0;
        for (size_t i = 0; i < stride; i++)
            row[i] = (uint8_t)(src[i] + ref_pred(f, row, up, i, 3));
    }
    free(raw);
    if (!ok) {
        free(px);
        return NULL;
    }
    return px;
}

/* ---- PNG ---- */

static void test_encode_reference(void)
{
    struct rgb8 img = pattern(37, 23), back;
    struct err e = {0};
    uint8_t *png;
    size_t n;
    CHECK(png_encode(&img, &png, &n, &e) == 0);
    int w, h;
    uint8_t *px = ref_decode_rgb(png, n, &w, &h);
    CHECK(px != NULL);
    CHECK(w == 37 && h == 23);
    CHECK(px && memcmp(px, img.px, 37 * 23 * 3) == 0);
    CHECK(png_decode(png, n, "g.png", &back, &e) == 0);
    CHECK(same_image(&img, &back));
    free(px);
    free(png);
    image_free(&back);
    image_free(&img);
}

static void test_odd_sizes(void)
{
    const int sizes[][2] = {{1, 1}, {3, 7}, {7, 3}, {1, 40}, {40, 1}, {255, 2}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        struct rgb8 img = pattern(sizes[i][0], sizes[i][1]), back;
        struct err e = {0};
        uint8_t *png;
        size_t n;
        int w, h;
        CHECK(png_encode(&img, &png, &n, &e) == 0);
        CHECK(png_decode(png, n, "odd.png", &back, &e) == 0);
        CHECK(same_image(&img, &back));
        uint8_t *px = ref_decode_rgb(png, n, &w, &h);
        CHECK(px && w == img.w && h == img.h && !memcmp(px, img.px, (size_t)w * h * 3));
        free(px);
        free(png);
        image_free(&back);
        image_free(&img);
    }
    struct rgb8 empty = {0};
    struct err e = {0};
    uint8_t *png = (uint8_t *)&e;
    size_t n = 1;
    CHECK(png_encode(&empty, &png, &n, &e) == -1 && png == NULL && n == 0);
}

/* Every colour type with every filter (and all five mixed) decodes to the expected RGB. */
static void test_filters_and_color_types(void)
{
    const int types[4] = {0, 2, 4, 6}, channels[4] = {1, 3, 2, 4};
    const int w = 6, h = 5;
    for (int t = 0; t < 4; t++) {
        int ch = channels[t];
        uint8_t s[6 * 5 * 4] = {0}, want[6 * 5 * 3];
        for (int i = 0; i < w * h * ch; i++)
            s[i] = (uint8_t)(i * 97 + t * 31 + (i % 7) * 40);
        for (int i = 0; i < w * h; i++)
            for (int k = 0; k < 3; k++)
                want[i * 3 + k] = ch < 3 ? s[i * ch] : s[i * ch + k];
        for (int mode = -1; mode <= 4; mode++) {
            size_t raw_len;
            uint8_t *raw = ref_filter(s, w, h, ch, mode, &raw_len);
            struct buf b = ref_png(w, h, 8, types[t], 0, raw, raw_len, 0, NULL);
            struct rgb8 out;
            struct err e = {0};
            int rc = png_decode(b.p, b.n, "f.png", &out, &e);
            CHECK(rc == 0);
            CHECK(rc == 0 && out.w == w && out.h == h && !memcmp(out.px, want, sizeof want));
            if (rc)
                fprintf(stderr, "  color type %d filter %d: %s\n", types[t], mode, e.msg);
            image_free(&out);
            free(b.p);
            free(raw);
        }
    }
}

/* Decode a PNG built around `raw`; returns png_decode's result, e holds the message. */
static int try_png(uint32_t w, uint32_t h, int depth, int ct, int interlace, const uint8_t *raw,
                   size_t raw_len, size_t split, const char *extra, struct err *e)
{
    struct buf b = ref_png(w, h, depth, ct, interlace, raw, raw_len, split, extra);
    struct rgb8 out;
    memset(e, 0, sizeof *e);
    int rc = png_decode(b.p, b.n, "t.png", &out, e);
    if (rc != 0)
        rc = out.px == NULL && out.w == 0 ? -1 : -2; /* -2: a failure that left pixels behind */
    image_free(&out);
    free(b.p);
    return rc;
}

/* A PNG whose only IDAT holds the first half of a valid zlib stream must fail as truncated. */
static int cut_stream_fails(const uint8_t *raw, size_t raw_len)
{
    uLongf zn = compressBound(raw_len);
    uint8_t *z = malloc(zn), ihdr[13] = {0, 0, 0, 9, 0, 0, 0, 8, 8, 2, 0, 0, 0};
    compress2(z, &zn, raw, raw_len, 9);
    struct buf b = {0};
    buf_add(&b, signature, 8);
    add_chunk(&b, "IHDR", ihdr, 13);
    add_chunk(&b, "IDAT", z, zn / 2);
    add_chunk(&b, "IEND", NULL, 0);
    struct rgb8 out;
    struct err e = {0};
    int ok = png_decode(b.p, b.n, "cut.png", &out, &e) == -1 && out.px == NULL &&
             has(&e, "truncated PNG: image data ends");
    free(z);
    free(b.p);
    return ok;
}

static void test_chunks(void)
{
    struct rgb8 img = pattern(9, 8);
    size_t raw_len;
    uint8_t *raw = ref_filter(img.px, 9, 8, 3, -1, &raw_len);
    struct err e;
    CHECK(try_png(9, 8, 8, 2, 0, raw, raw_len, 5, NULL, &e) == 0); /* many small IDATs */
    CHECK(try_png(9, 8, 8, 2, 0, raw, raw_len, 1, "tEXt", &e) == 0);
    CHECK(try_png(9, 8, 8, 2, 0, raw, raw_len, 0, "PLTE", &e) == 0); /* suggested palette */
    CHECK(try_png(9, 8, 8, 0, 0, raw, 8 * 10, 0, "PLTE", &e) == -1 && has(&e, "PLTE"));
    CHECK(try_png(9, 8, 8, 2, 0, raw, raw_len, 0, "ABCD", &e) == -1);
    CHECK(has(&e, "unknown critical chunk ABCD"));
    CHECK(try_png(9, 8, 8, 2, 0, raw, raw_len, 0, "IHDR", &e) == -1 && has(&e, "IHDR"));
    CHECK(try_png(9, 8, 8, 2, 0, raw, raw_len - 1, 0, NULL, &e) == -1); /* one byte short */
    CHECK(has(&e, "expected"));
    CHECK(cut_stream_fails(raw, raw_len));
    uint8_t *more = calloc(raw_len + 1, 1);
    memcpy(more, raw, raw_len);
    CHECK(try_png(9, 8, 8, 2, 0, more, raw_len + 1, 0, NULL, &e) == -1); /* one byte extra */
    CHECK(has(&e, "larger"));
    CHECK(try_png(9, 8, 8, 2, 0, more, raw_len + 1, 3, NULL, &e) == -1);
    free(more);
    raw[3 * (9 * 3 + 1)] = 7; /* row 3's filter byte */
    CHECK(try_png(9, 8, 8, 2, 0, raw, raw_len, 0, NULL, &e) == -1);
    CHECK(has(&e, "bad filter type 7 on row 3"));
    free(raw);
    image_free(&img);
}

static void test_unsupported_headers(void)
{
    uint8_t raw[64] = {0};
    struct err e;
    CHECK(try_png(2, 2, 8, 2, 1, raw, 15, 0, NULL, &e) == 0); /* Adam7: passes 1, 6 and 7 */
    CHECK(try_png(2, 2, 8, 2, 1, raw, 14, 0, NULL, &e) == -1 && has(&e, "expected 15"));
    CHECK(try_png(2, 2, 8, 2, 2, raw, 14, 0, NULL, &e) == -1 && has(&e, "bad interlace method 2"));
    CHECK(try_png(2, 2, 16, 2, 0, raw, 26, 0, NULL, &e) == 0);
    CHECK(try_png(2, 2, 4, 0, 0, raw, 4, 0, NULL, &e) == 0);
    CHECK(try_png(2, 2, 3, 0, 0, raw, 4, 0, NULL, &e) == -1 && has(&e, "bit depth 3 is not allowed"));
    CHECK(try_png(2, 2, 16, 3, 0, raw, 6, 0, NULL, &e) == -1 && has(&e, "bit depth 16 is not allowed"));
    CHECK(try_png(2, 2, 4, 2, 0, raw, 6, 0, NULL, &e) == -1 && has(&e, "bit depth 4 is not allowed"));
    CHECK(try_png(2, 2, 8, 3, 0, raw, 6, 0, NULL, &e) == -1 && has(&e, "without a PLTE"));
    CHECK(try_png(2, 2, 8, 5, 0, raw, 6, 0, NULL, &e) == -1 && has(&e, "color type 5"));
    CHECK(try_png(0, 2, 8, 2, 0, raw, 2, 0, NULL, &e) == -1);
    CHECK(try_png(100000, 1, 8, 2, 0, raw, 64, 0, NULL, &e) == -1 && has(&e, "100000x1"));
    CHECK(try_png(0xffffffffu, 0xffffffffu, 8, 6, 0, raw, 64, 0, NULL, &e) == -1);
    CHECK(try_png(20000, 20000, 8, 2, 0, raw, 64, 0, NULL, &e) == -1 && has(&e, "pixels"));
    CHECK(!strcmp(e.file, "t.png") && e.line == 0);
}

/* ---- the other PNG formats: each decodes to the same pixels as an 8-bit RGB of them ---- */

/* Append the samples of pixel (x, y) of img (with palette index idx) in colour type ct at depth
   bits, packed MSB first into row at sample position *k. */
static void put_sample(uint8_t *row, size_t *k, int depth, unsigned v)
{
    if (depth == 16) {
        row[*k * 2] = (uint8_t)(v >> 8);
        row[*k * 2 + 1] = (uint8_t)v;
    } else if (depth == 8) {
        row[*k] = (uint8_t)v;
    } else {
        size_t bit = *k * (size_t)depth;
        row[bit / 8] |= (uint8_t)(v << (8 - depth - (int)(bit % 8)));
    }
    (*k)++;
}

/* A PNG of img's pixels in colour type ct at depth: RGB(A) samples scaled up to 16 bits by x257,
   gray from the red channel (which the caller keeps a multiple of 255 / (2^depth - 1)), palette
   indices from idx with plte. Rows unfiltered (filter 0), Adam7 when interlace. */
static struct buf format_png(const struct rgb8 *img, int ct, int depth, int interlace, const uint8_t *idx,
                             const uint8_t *plte, int plte_n)
{
    static const int x0[7] = {0, 4, 0, 2, 0, 1, 0}, y0[7] = {0, 0, 4, 0, 2, 0, 1};
    static const int dx[7] = {8, 8, 4, 4, 2, 2, 1}, dy[7] = {8, 8, 8, 4, 4, 2, 2};
    int ch = ct == 2 ? 3 : ct == 6 ? 4 : ct == 4 ? 2 : 1, w = img->w, h = img->h;
    unsigned top = (1u << depth) - 1;
    struct buf raw = {0}, b = {0};
    for (int p = 0; p < (interlace ? 7 : 1); p++) {
        int px0 = interlace ? x0[p] : 0, py0 = interlace ? y0[p] : 0;
        int pdx = interlace ? dx[p] : 1, pdy = interlace ? dy[p] : 1;
        if (px0 >= w || py0 >= h)
            continue;
        size_t stride = ((size_t)((w - px0 + pdx - 1) / pdx) * ch * depth + 7) / 8;
        uint8_t *row = malloc(stride + 1);
        for (int y = py0; y < h; y += pdy) {
            memset(row, 0, stride + 1);
            size_t k = 0;
            for (int x = px0; x < w; x += pdx) {
                const uint8_t *q = img->px + ((size_t)y * w + x) * 3;
                if (ct == 3) {
                    put_sample(row + 1, &k, depth, idx[(size_t)y * w + x]);
                } else if (ct == 0 || ct == 4) {
                    put_sample(row + 1, &k, depth, depth == 16 ? q[0] * 257u : q[0] * top / 255);
                } else {
                    for (int c = 0; c < 3; c++)
                        put_sample(row + 1, &k, depth, depth == 16 ? q[c] * 257u : q[c]);
                }
                if (ct == 4 || ct == 6)
                    put_sample(row + 1, &k, depth, top / 3); /* alpha: dropped */
            }
            buf_add(&raw, row, stride + 1);
        }
        free(row);
    }
    uint8_t ihdr[13] = {0};
    put32(ihdr, (uint32_t)w);
    put32(ihdr + 4, (uint32_t)h);
    ihdr[8] = (uint8_t)depth;
    ihdr[9] = (uint8_t)ct;
    ihdr[12] = (uint8_t)interlace;
    buf_add(&b, signature, 8);
    add_chunk(&b, "IHDR", ihdr, 13);
    if (plte)
        add_chunk(&b, "PLTE", plte, (size_t)plte_n * 3);
    uLongf zn = compressBound(raw.n);
    uint8_t *z = malloc(zn);
    compress2(z, &zn, raw.p, raw.n, 9);
    add_chunk(&b, "IDAT", z, zn);
    add_chunk(&b, "IEND", NULL, 0);
    free(z);
    free(raw.p);
    return b;
}

static int decodes_to(const struct buf *b, const struct rgb8 *want)
{
    struct rgb8 out;
    struct err e = {0};
    int ok = png_decode(b->p, b->n, "f.png", &out, &e) == 0 && same_image(&out, want);
    if (!ok)
        fprintf(stderr, "  decode: %s\n", e.msg);
    image_free(&out);
    return ok;
}

static void test_other_formats(void)
{
    static const int sizes[][2] = {{1, 1}, {2, 1}, {1, 5}, {3, 2}, {8, 8}, {9, 7}, {17, 13}};
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        int w = sizes[s][0], h = sizes[s][1];
        for (int il = 0; il <= 1; il++) {
            struct rgb8 img = pattern(w, h);
            struct buf b;
            b = format_png(&img, 2, 8, il, NULL, NULL, 0);
            CHECK(decodes_to(&b, &img));
            free(b.p);
            for (int ct = 2; ct <= 6; ct += 4) {
                b = format_png(&img, ct, 16, il, NULL, NULL, 0);
                CHECK(decodes_to(&b, &img));
                free(b.p);
            }
            b = format_png(&img, 6, 8, il, NULL, NULL, 0);
            CHECK(decodes_to(&b, &img));
            free(b.p);
            /* palette images at every depth: 2^depth colours, the pixels' indices a pattern */
            for (int depth = 1; depth <= 8; depth *= 2) {
                int n = 1 << depth;
                uint8_t plte[768], *idx = malloc((size_t)w * h);
                for (int i = 0; i < n * 3; i++)
                    plte[i] = (uint8_t)(i * 37 + 11);
                for (int i = 0; i < w * h; i++) {
                    idx[i] = (uint8_t)((i * 7 + i / w) % n);
                    memcpy(img.px + (size_t)i * 3, plte + idx[i] * 3, 3);
                }
                b = format_png(&img, 3, depth, il, idx, plte, n);
                CHECK(decodes_to(&b, &img));
                free(b.p);
                free(idx);
            }
            /* gray (and gray + alpha) at every depth: levels that survive the scaling both ways */
            for (int depth = 1; depth <= 16; depth *= 2) {
                unsigned top = (1u << depth) - 1;
                for (int i = 0; i < w * h; i++) {
                    unsigned level =
                        depth == 16 ? (unsigned)(i * 29 % 256) : (unsigned)(i * 5 % (top + 1)) * 255 / top;
                    memset(img.px + (size_t)i * 3, (int)level, 3);
                }
                b = format_png(&img, 0, depth, il, NULL, NULL, 0);
                CHECK(decodes_to(&b, &img));
                free(b.p);
                if (depth >= 8) {
                    b = format_png(&img, 4, depth, il, NULL, NULL, 0);
                    CHECK(decodes_to(&b, &img));
                    free(b.p);
                }
            }
            image_free(&img);
        }
    }
    /* a palette index past the PLTE's entries is refused */
    struct rgb8 img = pattern(2, 2);
    uint8_t idx[4] = {0, 1, 2, 3}, plte[6] = {1, 2, 3, 4, 5, 6};
    struct buf b = format_png(&img, 3, 8, 0, idx, plte, 2);
    struct rgb8 out;
    struct err e = {0};
    CHECK(png_decode(b.p, b.n, "f.png", &out, &e) == -1 && has(&e, "palette index 2 of 2") && !out.px);
    free(b.p);
    image_free(&img);
}

/* A misplaced or malformed PLTE in a palette image: the message says which, not just "bad". */
static int plte_fails(const char *order, size_t plte_len, const char *want)
{
    static const uint8_t ihdr[13] = {0, 0, 0, 2, 0, 0, 0, 1, 8, 3, 0, 0, 0}, raw[3] = {0, 0, 0};
    uint8_t plte[771] = {0}, z[64];
    uLongf zn = sizeof z;
    compress2(z, &zn, raw, sizeof raw, 9);
    struct buf b = {0};
    buf_add(&b, signature, 8);
    add_chunk(&b, "IHDR", ihdr, 13);
    for (const char *o = order; *o; o++)
        if (*o == 'P')
            add_chunk(&b, "PLTE", plte, plte_len);
        else
            add_chunk(&b, "IDAT", z, zn);
    add_chunk(&b, "IEND", NULL, 0);
    struct rgb8 out;
    struct err e = {0};
    int ok = png_decode(b.p, b.n, "p.png", &out, &e) == -1 && has(&e, want);
    if (!ok)
        fprintf(stderr, "  PLTE order %s, %zu bytes: %s\n", order, plte_len, e.msg);
    image_free(&out);
    free(b.p);
    return ok;
}

static void test_plte_messages(void)
{
    CHECK(plte_fails("PIP", 3, "PLTE chunk after the image data"));
    CHECK(plte_fails("PPI", 3, "second PLTE chunk"));
    CHECK(plte_fails("PI", 4, "PLTE chunk of 4 bytes"));
    CHECK(plte_fails("PI", 771, "PLTE chunk of 771 bytes"));
}

static void test_damaged_files(void)
{
    struct rgb8 img = pattern(3, 7), out;
    struct err e = {0};
    uint8_t *png;
    size_t n;
    CHECK(png_encode(&img, &png, &n, &e) == 0);
    int prefix_fail = 0, flip_fail = 0;
    for (size_t k = 0; k < n; k++) {
        memset(&e, 0, sizeof e);
        prefix_fail += png_decode(png, k, "p.png", &out, &e) == -1 && out.px == NULL && e.msg[0];
        image_free(&out);
    }
    CHECK(prefix_fail == (int)n);
    uint8_t *bad = malloc(n);
    for (size_t k = 0; k < n; k++) {
        memcpy(bad, png, n);
        bad[k] ^= 0x10;
        flip_fail += png_decode(bad, n, "f.png", &out, &e) == -1 && out.px == NULL;
        image_free(&out);
    }
    CHECK(flip_fail == (int)n);
    memcpy(bad, png, n);
    bad[8 + 8 + 2] ^= 1; /* inside IHDR's width */
    CHECK(png_decode(bad, n, "f.png", &out, &e) == -1 && has(&e, "CRC mismatch in chunk IHDR"));
    memcpy(bad, png, n);
    bad[1] = 'Q';
    CHECK(png_decode(bad, n, "f.png", &out, &e) == -1 && has(&e, "bad signature"));
    CHECK(png_decode(png, n - 1, "f.png", &out, &e) == -1 && has(&e, "truncated"));
    CHECK(png_decode(png, n - 12, "f.png", &out, &e) == -1 && has(&e, "missing IEND"));
    memcpy(bad, png, n);
    put32(bad + 8, 0x7ffffff0u); /* IHDR claims a huge length */
    CHECK(png_decode(bad, n, "f.png", &out, &e) == -1);
    memcpy(bad, png, n);
    put32(bad + 8, 0x90000000u);
    CHECK(png_decode(bad, n, "f.png", &out, &e) == -1 && has(&e, "length"));
    CHECK(png_decode(png, n, "ok.png", &out, &e) == 0 && same_image(&img, &out));
    image_free(&out);
    free(bad);
    free(png);
    image_free(&img);
}

int main(void)
{
    test_encode_reference();
    test_odd_sizes();
    test_filters_and_color_types();
    test_chunks();
    test_unsupported_headers();
    test_other_formats();
    test_plte_messages();
    test_damaged_files();
    return check_report("test_png");
}
