/* report: report.html of a compare job: one self-contained page (images inline as data URIs). */
#ifndef REPORT_H
#define REPORT_H

#include "compare.h"

/* The page for a finished compare job whose images are in dir (OUT/<name>/): the chart, per
   scene the images side by side at each sweep point with their sample counts, 4x crops of the
   region with the largest relative error (a soft shadow in our scenes), error maps, one
   stability line per variant, and the table. Reads the images and references from disk.
   Returns a malloc'd string (caller frees), or NULL with e filled. */
char *report_html(const struct compare *c, const char *dir, struct err *e);

/* The page's CSS, for the other pages of a study (a suite's report.html). */
extern const char report_style[];

#endif
