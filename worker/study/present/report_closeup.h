/* report_closeup: the compare report's close look at one sweep point: zoomed crops of the window
   where the images differ most from the reference, and the relative error maps with their scale. */
#ifndef REPORT_CLOSEUP_H
#define REPORT_CLOSEUP_H

#include "base/sbuf.h"
#include "study/load/compare_model.h"
#include "image/image.h"

/* Crops and error maps of scene s at sweep point p, every variant and seed (the images read from
   dir), against the reference: ref its 8-bit display image, reff its floats when linear, else
   NULL (the maps are then of the 8-bit display values, and say so). 0, or -1 with e filled. */
int report_closeup(struct sbuf *b, const struct compare *c, int s, int p, const char *dir,
                   const struct rgb8 *ref, const struct rgbf *reff, struct err *e);

#endif
