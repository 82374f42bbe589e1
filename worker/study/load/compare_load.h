/* compare_load: a compare job's file read into its model (compare_model.h), every check done
   before anything renders. */
#ifndef COMPARE_LOAD_H
#define COMPARE_LOAD_H

#include "compare_model.h"
#include "scenefile/yamlx.h"

/* Load, validate and expand the compare job at path into a new struct compare. Everything a
   render needs is checked here (keys, values, scenes, reference images, set sizes), so a bad
   job fails before anything renders. NULL with e = "file:line:col: key: message". */
struct compare *compare_load(const char *path, struct err *e);

/* compare_load of the job file at path already parsed into d (jobfile_open), which is read, not
   kept. */
struct compare *compare_load_doc(const struct ydoc *d, const char *path, struct err *e);

/* compare_load_doc reading its scenes and references through in (a suite's, shared by its
   studies, which outlives the result): a file another study read is not read again. */
struct compare *compare_load_in(const struct ydoc *d, const char *path, struct study_inputs *in,
                                struct err *e);

#endif
