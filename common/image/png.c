/* png: an 8-bit RGB PNG encoder with adaptive row filters (the decoder is png_decode.c). */
#include "png.h"
#include "png_internal.h"

#include <stdlib.h>
#include <string.h>

#define ZLIB_CONST
#include <zlib.h>

#define PNG_IDAT_MAX (1u << 20) /* zlib bytes per IDAT chunk we write */
#define PNG_ZLIB_LEVEL 6

/* Heuristic from the PNG spec (12.8): the smaller the sum of |signed byte|, the better. */
static size_t filter_cost(const uint8_t *row, size_t n)
{
    size_t sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += (size_t)abs((int8_t)row[i]);
    return sum;
}

/* Fill raw with h rows of (filter byte, filtered pixels), choosing each row's filter. */
static int filter_image(const struct rgb8 *img, uint8_t *raw, struct err *e)
{
    size_t stride = (size_t)img->w * 3;
    uint8_t *scratch = malloc(2 * stride);
    uint8_t *zero = calloc(stride, 1);
    if (!scratch || !zero) {
        free(scratch);
        free(zero);
        return err_set(e, NULL, 0, 0, "out of memory encoding PNG");
    }
    for (int y = 0; y < img->h; y++) {
        const uint8_t *cur = img->px + (size_t)y * stride;
        const uint8_t *prev = y ? cur - stride : zero;
        uint8_t *best = scratch, *cand = scratch + stride;
        size_t best_cost = SIZE_MAX;
        int best_f = 0;
        for (int f = 0; f <= 4; f++) {
            filter_row(f, cur, prev, stride, 3, cand);
            size_t cost = filter_cost(cand, stride);
            if (cost < best_cost) {
                uint8_t *t = best;
                best = cand;
                cand = t;
                best_cost = cost;
                best_f = f;
            }
        }
        uint8_t *dst = raw + (size_t)y * (stride + 1);
        dst[0] = (uint8_t)best_f;
        memcpy(dst + 1, best, stride);
    }
    free(scratch);
    free(zero);
    return 0;
}

/* Write one chunk (length, type, data, CRC over type and data) at p; returns the end. data NULL:
   the n bytes are already in place at p + 8. */
static uint8_t *put_chunk(uint8_t *p, const char *type, const uint8_t *data, uint32_t n)
{
    put_be32(p, n);
    memcpy(p + 4, type, 4);
    if (n && data)
        memcpy(p + 8, data, n);
    uLong crc = crc32(0L, p + 4, 4 + n);
    put_be32(p + 8 + n, (uint32_t)crc);
    return p + 12 + n;
}

int png_encode(const struct rgb8 *img, uint8_t **out, size_t *out_len, struct err *e)
{
    return png_encode_text(img, NULL, 0, out, out_len, e);
}

/* The zlib stream is split over IDAT chunks of at most 1 MiB. */
int png_encode_text(const struct rgb8 *img, const struct img_attr *texts, size_t ntexts, uint8_t **out,
                    size_t *out_len, struct err *e)
{
    *out = NULL;
    *out_len = 0;
    if (!img->px || img->w < 1 || img->h < 1 || img->w > IMAGE_MAX_SIDE || img->h > IMAGE_MAX_SIDE)
        return err_set(e, NULL, 0, 0, "cannot encode PNG: bad image %dx%d", img->w, img->h);
    size_t text_len = 0;
    for (size_t i = 0; i < ntexts; i++) {
        size_t kl = strlen(texts[i].key), vl = strlen(texts[i].value);
        if (kl < 1 || kl > 79 || vl > 65536) /* spec 11.3.4.3: a keyword is 1 to 79 bytes */
            return err_set(e, NULL, 0, 0, "cannot encode PNG: text \"%.20s\" too long", texts[i].key);
        text_len += 12 + kl + 1 + vl;
    }
    size_t raw_len = (size_t)img->h * ((size_t)img->w * 3 + 1);
    uLong z_len = compressBound((uLong)raw_len);
    uint8_t *raw = malloc(raw_len);
    uint8_t *z = malloc(z_len);
    uint8_t *buf = NULL;
    if (!raw || !z) {
        err_set(e, NULL, 0, 0, "out of memory encoding PNG");
        goto done;
    }
    if (filter_image(img, raw, e) < 0)
        goto done;
    int zr = compress2(z, &z_len, raw, (uLong)raw_len, PNG_ZLIB_LEVEL);
    if (zr != Z_OK) {
        err_set(e, NULL, 0, 0, "cannot encode PNG: zlib error %d", zr);
        goto done;
    }
    size_t n_idat = (z_len + PNG_IDAT_MAX - 1) / PNG_IDAT_MAX;
    size_t total = sizeof png_signature + (12 + 13) + text_len + 12 * n_idat + z_len + 12;
    buf = malloc(total);
    if (!buf) {
        err_set(e, NULL, 0, 0, "out of memory encoding PNG");
        goto done;
    }
    uint8_t ihdr[13] = {0, 0, 0, 0, 0, 0, 0, 0, 8, 2, 0, 0, 0}; /* depth 8, RGB, no interlace */
    put_be32(ihdr, (uint32_t)img->w);
    put_be32(ihdr + 4, (uint32_t)img->h);
    uint8_t *p = buf;
    memcpy(p, png_signature, sizeof png_signature);
    p = put_chunk(p + sizeof png_signature, "IHDR", ihdr, sizeof ihdr);
    for (size_t i = 0; i < ntexts; i++) {
        /* tEXt: keyword, a zero byte, the text, written in place; put_chunk adds the frame */
        size_t kl = strlen(texts[i].key), vl = strlen(texts[i].value);
        memcpy(p + 8, texts[i].key, kl + 1);
        memcpy(p + 8 + kl + 1, texts[i].value, vl);
        p = put_chunk(p, "tEXt", NULL, (uint32_t)(kl + 1 + vl));
    }
    for (size_t off = 0; off < z_len; off += PNG_IDAT_MAX) {
        size_t n = z_len - off < PNG_IDAT_MAX ? z_len - off : PNG_IDAT_MAX;
        p = put_chunk(p, "IDAT", z + off, (uint32_t)n);
    }
    put_chunk(p, "IEND", NULL, 0);
    *out = buf;
    *out_len = total;
    buf = NULL;
done:
    free(buf);
    free(raw);
    free(z);
    return *out ? 0 : -1;
}
