/* png_internal: what the PNG encoder (png.c) and decoder (png_decode.c) share: the signature,
   big-endian words and the row filters (PNG spec 9). Internal to common/. */
#ifndef PNG_INTERNAL_H
#define PNG_INTERNAL_H

#include <stdint.h>
#include <stdlib.h>

#define PNG_CHUNK_MAX 0x7fffffffu /* spec: a chunk's data is at most 2^31 - 1 bytes */

static const uint8_t png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

static inline uint32_t get_be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static inline void put_be32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

/* The Paeth predictor (PNG spec 9.4): whichever of left, up, up-left is nearest a + b - c. */
static inline int paeth(int a, int b, int c)
{
    int p = a + b - c;
    int pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
    if (pa <= pb && pa <= pc)
        return a;
    return pb <= pc ? b : c;
}

/* Prediction for filter f from left a, up b and up-left c (all unfiltered bytes). */
static inline uint8_t predict(int f, int a, int b, int c)
{
    switch (f) {
    case 1:
        return (uint8_t)a;
    case 2:
        return (uint8_t)b;
    case 3:
        return (uint8_t)((a + b) / 2);
    case 4:
        return (uint8_t)paeth(a, b, c);
    default:
        return 0;
    }
}

/* Filter row cur (prev is the row above, zeros for the first) with filter f into out. */
static inline void filter_row(int f, const uint8_t *cur, const uint8_t *prev, size_t n, size_t bpp,
                              uint8_t *out)
{
    for (size_t i = 0; i < n; i++) {
        int a = i >= bpp ? cur[i - bpp] : 0;
        int c = i >= bpp ? prev[i - bpp] : 0;
        out[i] = (uint8_t)(cur[i] - predict(f, a, prev[i], c));
    }
}

/* Undo filter f on row in place; its left neighbours are already reconstructed. */
static inline void unfilter_row(int f, uint8_t *row, const uint8_t *prev, size_t n, size_t bpp)
{
    if (f == 0)
        return;
    for (size_t i = 0; i < n; i++) {
        int a = i >= bpp ? row[i - bpp] : 0;
        int c = i >= bpp ? prev[i - bpp] : 0;
        row[i] = (uint8_t)(row[i] + predict(f, a, prev[i], c));
    }
}

#endif
