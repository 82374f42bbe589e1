/* compare_suite_load: a suite's file (`studies:`) and every study it lists read into the model
   (compare_model.h's struct compare_suite), each study checked as a compare job of its own. */
#ifndef COMPARE_SUITE_LOAD_H
#define COMPARE_SUITE_LOAD_H

#include "compare_model.h"
#include "scenefile/yamlx.h"

/* Load the suite at path and every study it lists (paths relative to the suite's file), each
   fully validated as compare_load does, so a bad study fails before anything renders. NULL with
   e = "file:line:col: key: message" at the suite's key or inside the study file at fault. */
struct compare_suite *compare_suite_load(const char *path, struct err *e);

/* compare_suite_load of the suite at path already parsed into d (jobfile_open), which is read,
   not kept. */
struct compare_suite *compare_suite_load_doc(const struct ydoc *d, const char *path, struct err *e);

#endif
