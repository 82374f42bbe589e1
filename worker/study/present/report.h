/* report: report.html of a compare job: one self-contained page (images inline as data URIs). */
#ifndef REPORT_H
#define REPORT_H

#include "study/load/compare_model.h"
#include "base/sbuf.h"

/* The page for a finished compare job whose images are in dir (OUT/<name>/): the chart, per
   scene the reference and the images side by side at each sweep point with their sample counts,
   zoomed crops of the region with the largest relative error (a soft shadow in our scenes),
   relative error maps with their colour bar, one stability line per variant, and the table. Every
   seed's images are on the page, at an integer zoom, with a seed selector, an A/B toggle against
   the reference and click to enlarge (report_view). Reads the images and references from disk.
   Returns a malloc'd string (caller frees), or NULL with e filled. */
char *report_html(const struct compare *c, const char *dir, struct err *e);

/* A page's opening up to its <h1> (the page's CSS in its head) for a study, or a suite of
   n_studies (> 0), named name. */
void report_head(struct sbuf *b, const char *name, int n_studies);

/* "40 images = 2 scenes x 5 variants x 2 sweep points (sweep: threshold) x 2 seeds" */
void report_study_shape(struct sbuf *b, const struct compare *c);

/* <a href="href">text</a>, href relative to the page with every byte but letters, digits and
   "-._~/" percent-encoded (a file name with a quote, '#' or '%' still resolves), text escaped. */
void report_link(struct sbuf *b, const char *href, const char *text);

#endif
