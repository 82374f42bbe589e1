/* mask: rectangles and white-on-black images as per-pixel flags, with their bounding box. */
#include "mask.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

static int mask_alloc(struct img_mask *m, int w, int h, struct err *e)
{
    *m = (struct img_mask){w, h, NULL, w, h, 0, 0, 0};
    if (w < 1 || h < 1 || !(m->on = calloc((size_t)w * h, 1)))
        return err_set(e, NULL, 0, 0, "out of memory for a %dx%d mask", w, h);
    return 0;
}

/* Count m's pixels and find their bounding box; -1 with e filled when there is none. */
static int mask_finish(struct img_mask *m, struct err *e)
{
    m->count = 0;
    m->x0 = m->w, m->y0 = m->h, m->x1 = m->y1 = 0;
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++)
            if (m->on[(size_t)y * m->w + x]) {
                m->count++;
                m->x0 = x < m->x0 ? x : m->x0;
                m->y0 = y < m->y0 ? y : m->y0;
                m->x1 = x + 1 > m->x1 ? x + 1 : m->x1;
                m->y1 = y + 1 > m->y1 ? y + 1 : m->y1;
            }
    if (m->count == 0) {
        mask_free(m);
        return err_set(e, NULL, 0, 0, "the mask counts no pixel (white = counted)");
    }
    return 0;
}

int mask_rect(struct img_mask *m, int w, int h, const long rect[4], struct err *e)
{
    m->on = NULL;
    if (rect[0] < 0 || rect[1] < 0 || rect[2] > w || rect[3] > h)
        return err_set(e, NULL, 0, 0, "[%ld, %ld, %ld, %ld] reaches outside the %dx%d image", rect[0],
                       rect[1], rect[2], rect[3], w, h);
    if (rect[2] <= rect[0] || rect[3] <= rect[1])
        return err_set(e, NULL, 0, 0,
                       "[%ld, %ld, %ld, %ld] is empty (x1 > x0 and y1 > y0 are needed; x1 and y1 are "
                       "exclusive)",
                       rect[0], rect[1], rect[2], rect[3]);
    if (mask_alloc(m, w, h, e) < 0)
        return -1;
    for (long y = rect[1]; y < rect[3]; y++)
        memset(m->on + (size_t)y * w + rect[0], 1, (size_t)(rect[2] - rect[0]));
    return mask_finish(m, e);
}

int mask_from_image(struct img_mask *m, const struct rgb8 *img, struct err *e)
{
    if (mask_alloc(m, img->w, img->h, e) < 0)
        return -1;
    for (size_t i = 0; i < (size_t)img->w * img->h; i++) {
        const uint8_t *p = img->px + 3 * i;
        m->on[i] = p[0] + p[1] + p[2] >= 3 * 128;
    }
    return mask_finish(m, e);
}

int mask_check_size(const struct img_mask *m, int w, int h, struct err *e)
{
    if (m->w != w || m->h != h)
        return err_set(e, NULL, 0, 0, "the mask is %dx%d but the images are %dx%d", m->w, m->h, w, h);
    return 0;
}

int mask_parse_rect(const char *text, long rect[4])
{
    const char *p = text;
    for (int i = 0; i < 4; i++) {
        char *end;
        errno = 0;
        if (!(*p >= '0' && *p <= '9') && *p != '-')
            return -1;
        rect[i] = strtol(p, &end, 10);
        if (errno || end == p || rect[i] < -(1L << 30) || rect[i] > (1L << 30) || *end != (i < 3 ? ',' : 0))
            return -1;
        p = end + 1;
    }
    return 0;
}

void mask_free(struct img_mask *m)
{
    if (m) {
        free(m->on);
        m->on = NULL;
    }
}

int mask_crop_pair(const struct img_mask *m, const struct rgbf *ref, const struct rgbf *img,
                   struct rgbf *ref_out, struct rgbf *img_out, struct err *e)
{
    int w = m->x1 - m->x0, h = m->y1 - m->y0;
    if (image_f_alloc(ref_out, w, h, e) < 0 || image_f_alloc(img_out, w, h, e) < 0) {
        image_f_free(ref_out);
        return -1;
    }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t from = ((size_t)(y + m->y0) * ref->w + x + m->x0) * 3, to = ((size_t)y * w + x) * 3;
            int on = mask_on(m, x + m->x0, y + m->y0);
            for (int c = 0; c < 3; c++) {
                ref_out->px[to + c] = ref->px[from + c];
                img_out->px[to + c] = on ? img->px[from + c] : ref->px[from + c];
            }
        }
    return 0;
}
