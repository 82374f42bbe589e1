/* compare: running a loaded compare job (compare_model.h): its references (cached), each
   combination an ordinary render scored against its scene's reference, then the verdict and the
   summary, chart, verdict.json and report. The plan is only read (const); a render writes its row
   of the results, compare_write_outputs the verdict. */
#ifndef COMPARE_H
#define COMPARE_H

#include <stddef.h>

#include "job/run.h"
#include "study/load/compare_model.h"

/* Render every reference (or reuse the cache under OUT/.cache/) and every combination into
   c->results, then judge and write summary.csv, chart.svg and report.html under OUT/<name>/
   (compare_write_outputs); c's plan is not changed. Every render keeps its float
   image (<stem>.exr) beside its PNG; errors are measured on those linear values. Returns 0, 1 when a render
   or write failed, 2 on bad input found late (a reference image); e says why. Prints one
   progress line per combination when o->progress and not o->quiet. */
int compare_run(struct compare *c, const struct run_opts *o, struct err *e);

/* Render combination i of plan c alone (the queue's fan-out: one render per queue entry) into its
   row of r (c's results), its scene's reference prepared first into r->refs (reused from the cache
   when there). 0, 1 or 2 as compare_run. */
int compare_run_item(const struct compare *c, struct study_results *r, int i, const struct run_opts *o,
                     struct err *e);

/* Combination i's job as compare_run_item renders it (its reference file and hash set), its scene's
   reference prepared first; for a queue that renders it in row parts and merges them (the merged
   image and sidecar are then current for compare_run_item). 0, 1 or 2 as compare_run. */
int compare_item_job(const struct compare *c, struct study_results *r, int i, const struct run_opts *o,
                     struct job *j, struct err *e);

/* From a finished study (every item's figures filled, its images and float copies in dir, each
   reference's path and noise in c->results.refs: compare_ref_prepare or compare_ref_measure): the
   verdict (verdict_from_compare, into c->verdict: the one member of c this writes), then summary.csv,
   chart.svg (report_chart_svg), verdict.json (verdict_json_text) and report.html (report_html) under dir's
   lock. The gather of a study spread over a queue calls this as compare_run does. 0, or -1 with e filled. */
int compare_write_outputs(struct compare *c, const char *dir, const struct run_opts *o, struct err *e);

/* The line that ends a compare job's run: its images, references, time, output folder and the
   verdict at equal CPU time ("compare: 120 images (2 scenes x ...), references: 1 rendered, ...,
   41 s -> out/compare/; at equal CPU time: ..."). */
void compare_summary_line(const struct compare *c, double wall_s, const char *out_dir, char *buf, size_t n);

#endif
