/* verdict_load: a finished compare output folder (a study or a suite) read back for the verdict:
   its summary.csv (the columns compare writes), the images' sidecars and float images, and the
   reference with its halves where they are present. What is absent is named, not guessed. */
#ifndef VERDICT_LOAD_H
#define VERDICT_LOAD_H

#include <stddef.h>

#include "base/err.h"
#include "study/judge/verdict.h"

/* The verdicts of the study or suite in dir (DIR/summary.csv; a suite's leading `study` column
   finds each study in DIR/<study>/), judged again by verdict_from_compare; *out a malloc'd array of
   *n studies (free each with verdict_study_free, then the array); job the folder's name. A check
   that needs what is missing (images, sidecars, the reference) is skipped and a warning of the
   scene says so. 0, or -1 with e filled (no summary.csv, a column missing, a row malformed, too
   many combinations) and nothing allocated (*out NULL, *n 0). */
int verdict_load_dir(const char *dir, struct verdict_study **out, int *n, char *job, size_t job_n,
                     struct err *e);

#endif
