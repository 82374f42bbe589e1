/* compare_suite_out: the texts of a suite's own files in OUT/<suite>/ (summary.csv, chart.svg,
   report.html), built from its finished studies. Internal to compare_suite. */
#ifndef COMPARE_SUITE_OUT_H
#define COMPARE_SUITE_OUT_H

#include "study/load/compare_model.h"
#include "verdict_out.h"

/* Every study's summary.csv (read back from dir/<study>/) with a leading `study` column, under
   one header. Malloc'd, or NULL with e filled. */
char *compare_suite_csv(const struct compare_suite *s, const char *dir, struct err *e);

/* Every study's chart (report_chart_svg) stacked in one SVG document. Malloc'd, NULL on no
   memory. */
char *compare_suite_chart_svg(const struct compare_suite *s);

/* The suite's page: the verdict of every study (v: one per study, in order), then per study its
   name, its chart inline and a link to its own report <study>/report.html. Malloc'd, or NULL
   with e filled. */
char *compare_suite_report_html(const struct compare_suite *s, const struct verdict_study *v, struct err *e);

#endif
