/* compare_suite: running a suite (compare_model.h's struct compare_suite): each study an ordinary
   compare job run into OUT/<suite>/<study>/, with the suite's verdict, summary, chart and report
   on top. */
#ifndef COMPARE_SUITE_H
#define COMPARE_SUITE_H

#include <stddef.h>

#include "job/run.h"
#include "study/load/compare_model.h"

/* Run every study with --out OUT/<suite name> (compare_run: images, references cached under
   OUT/<suite>/.cache/, the study's own files in OUT/<suite>/<study>/), then write the suite's
   verdict.json, summary.csv, chart.svg and report.html under OUT/<suite>/; nothing at the top
   when a study fails. Returns compare_run's 0, 1 or 2 with e filled. A progress line per study
   when o->progress and not o->quiet. */
int compare_suite_run(struct compare_suite *s, const struct run_opts *o, struct err *e);

/* The line that ends a suite's run: its images per study, references, time, output folder and
   the verdict at equal CPU time per study. */
void compare_suite_summary_line(const struct compare_suite *s, double wall_s, const char *out_dir, char *buf,
                                size_t n);

#endif
