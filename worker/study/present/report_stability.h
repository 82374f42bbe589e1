/* report_stability: the report's stability line per (scene, variant): the seeds' spread, and the
   verdict's findings (its slope, where error stops falling, the share of the error repeating in
   every seed, split into bias and pattern) printed, never recomputed. */
#ifndef REPORT_STABILITY_H
#define REPORT_STABILITY_H

#include "study/load/compare_model.h"

/* One line for people on (scene s, variant v) of c, from its figures and c->verdict (without a
   verdict or a reference: only what needs neither). Its length grows with the sweep: a malloc'd
   string (caller frees), NULL when out of memory. */
char *report_stability(const struct compare *c, int s, int v);

#endif
