/* jobfile_run: one run of an opened job file (jobfile.h), whatever its kind: the command line's
   and the queue's one way from a parsed job file to its outputs. */
#ifndef JOBFILE_RUN_H
#define JOBFILE_RUN_H

#include "job/jobfile.h"
#include "job/run.h"

/* What one jobfile_run did. */
struct jobfile_outcome {
    char name[JOB_NAME_MAX]; /* the job's name once known ("" when the compare job is invalid) */
    struct run_result rr;    /* a plain job's */
    struct err e;            /* the status is not 0: why */
    char line[4096];         /* a compare job's or suite's last line, on stderr already (unless
                                stopped): its error, or its summary */
};

/* Run f once with o. A plain job goes through run_job with the scene jobfile_open read; a compare
   job or suite is loaded from f's parsed document and run through the study (its summary or its
   error printed as one line on stderr). name_ok (optional) is asked, with arg, about the job's
   name before anything renders: 0 refuses it (name_ok said why), status 2. Returns the exit
   status: 0, 1 (a render failed) or 2 (bad input). */
int jobfile_run(const struct jobfile *f, const struct run_opts *o,
                int (*name_ok)(const char *name, void *arg), void *arg, struct jobfile_outcome *out);

#endif
