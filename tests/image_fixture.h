/* image_fixture: what test_png and test_ppm share: a growing byte buffer, a test image with
   ramps and noise, and comparisons. */
#ifndef IMAGE_FIXTURE_H
#define IMAGE_FIXTURE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/err.h"
#include "image/image.h"

struct buf {
    uint8_t *p;
    size_t n, cap;
};

static inline void buf_add(struct buf *b, const void *data, size_t n)
{
    if (b->n + n > b->cap) {
        b->cap = (b->n + n) * 2 + 64;
        b->p = realloc(b->p, b->cap);
        if (!b->p) {
            fprintf(stderr, "out of memory\n");
            exit(2);
        }
    }
    if (n)
        memcpy(b->p + b->n, data, n);
    b->n += n;
}

/* A w x h test image with smooth ramps plus some noise, so every filter has work to do. */
static inline struct rgb8 pattern(int w, int h)
{
    struct rgb8 img;
    image_alloc(&img, w, h, NULL);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint8_t *q = img.px + ((size_t)y * w + x) * 3;
            q[0] = (uint8_t)(x * 255 / (w > 1 ? w - 1 : 1));
            q[1] = (uint8_t)(y * 255 / (h > 1 ? h - 1 : 1));
            q[2] = (uint8_t)((x * 73 + y * 151 + x * y * 7) & 0xff);
        }
    return img;
}

static inline int same_image(const struct rgb8 *a, const struct rgb8 *b)
{
    return a->w == b->w && a->h == b->h && a->px && b->px &&
           memcmp(a->px, b->px, (size_t)a->w * a->h * 3) == 0;
}

static inline int has(const struct err *e, const char *s)
{
    return strstr(e->msg, s) != NULL;
}

#endif
