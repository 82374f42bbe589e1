/* study_main: the command line's and the queue's part of a compare job, plain or a suite of
   studies: load, run, then one line on stderr (the error, or the summary line). */
#ifndef STUDY_MAIN_H
#define STUDY_MAIN_H

#include <stddef.h>

#include "job/run.h"

/* Load, run and print the compare job (or suite) at path; errors as one line
   "file:line:col: message", then its summary line. name_ok (optional) is asked, with arg, about
   the loaded job's name before anything renders: 0 refuses the job (name_ok said why on stderr),
   exit status 2. Returns the exit status: 0, 1 or 2. */
int study_main(const char *path, const struct run_opts *o, int (*name_ok)(const char *name, void *arg),
               void *arg);

/* study_main for a job file read from `from` as if at `path` (a queue's claimed file); the line
   printed last (the error or the summary) is also copied into last (when not NULL), and the job's
   name, once it loaded, into name (when not NULL; left as it is when the job is invalid). */
int study_main_as(const char *from, const char *path, const struct run_opts *o, char *last, size_t n,
                  char *name, size_t name_n);

#endif
