/* dryrun: `worker JOB.yaml --dry-run`: what a job, compare job or suite would render and cost
   (samples, memory, CPU time from a short pilot), nothing rendered in full, nothing written. */
#ifndef DRYRUN_H
#define DRYRUN_H

#include "job/run.h"

/* Print the estimate of the job file at path on stdout (o: --out, --processes). 0, or 2 after
   one line on stderr (bad input, as rendering it would say). */
int dryrun_main(const char *path, const struct run_opts *o);

#endif
