/* compare_suite: a compare job made of study files (`studies:`), each an ordinary compare job run
   into OUT/<suite>/<study>/, with the suite's verdict, summary, chart and report on top. */
#ifndef COMPARE_SUITE_H
#define COMPARE_SUITE_H

#include <stddef.h>

#include "compare.h"

/* Most studies one suite may list, and most images all its studies may expand to together. */
#define COMPARE_SUITE_MAX_STUDIES 16
#define COMPARE_SUITE_MAX_ITEMS (4 * COMPARE_MAX_ITEMS)

struct compare_suite {
    char path[JOB_PATH_MAX];
    char name[JOB_NAME_MAX];
    int n_studies, n_items;
    struct compare *studies[COMPARE_SUITE_MAX_STUDIES]; /* owned, in the order listed */
    struct study_inputs *inputs; /* owned: the scenes and references of all studies, each read once */
};

/* Load the suite at path and every study it lists (paths relative to the suite's file), each
   fully validated as compare_load does, so a bad study fails before anything renders. NULL with
   e = "file:line:col: key: message" at the suite's key or inside the study file at fault. */
struct compare_suite *compare_suite_load(const char *path, struct err *e);

/* compare_suite_load of the suite at path already parsed into d (jobfile_open), which is read,
   not kept. */
struct compare_suite *compare_suite_load_doc(const struct ydoc *d, const char *path, struct err *e);
void compare_suite_free(struct compare_suite *s);

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
