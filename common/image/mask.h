/* mask: which pixels an error metric counts (a rectangle or a white-on-black image), so a study
   can measure part of the picture only. */
#ifndef MASK_H
#define MASK_H

#include <stddef.h>
#include <stdint.h>

#include "image.h"

/* w*h flags, row 0 at the top, non-zero = counted; [x0, x1) x [y0, y1) is the smallest rectangle
   holding every counted pixel; count > 0 (an empty mask is refused when made). Owned (mask_free). */
struct img_mask {
    int w, h;
    uint8_t *on;
    int x0, y0, x1, y1;
    size_t count;
};

/* The pixels x0 <= x < x1, y0 <= y < y1 of a w x h image. -1 with e filled (message only) when
   the rectangle is empty, inverted or reaches outside the image, or on no memory. */
int mask_rect(struct img_mask *m, int w, int h, const long rect[4], struct err *e);

/* The white pixels of img (the mean of R, G and B at least 128; black and dark grey are left
   out). -1 with e filled when no pixel is white or on no memory. */
int mask_from_image(struct img_mask *m, const struct rgb8 *img, struct err *e);

/* -1 with e filled (message only) unless m is w x h. */
int mask_check_size(const struct img_mask *m, int w, int h, struct err *e);

/* Parse "x0,y0,x1,y1" (whole numbers) into rect. 0, or -1 when it is not four such numbers. */
int mask_parse_rect(const char *text, long rect[4]);

void mask_free(struct img_mask *m);

/* Whether pixel (x, y) counts; every pixel when m is NULL. */
static inline int mask_on(const struct img_mask *m, int x, int y)
{
    return !m || m->on[(size_t)y * m->w + x];
}

/* ref and img (m's size) cut to m's bounding rectangle into ref_out and img_out (allocated here),
   img_out taking ref's value where m does not count, so those pixels carry no error: what a
   spectrum of the error is measured on. 0, or -1 with e filled on no memory. */
int mask_crop_pair(const struct img_mask *m, const struct rgbf *ref, const struct rgbf *img,
                   struct rgbf *ref_out, struct rgbf *img_out, struct err *e);

#endif
