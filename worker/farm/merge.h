/* merge: `worker merge JOB`: a job's part files joined into its image and sidecar. */
#ifndef MERGE_H
#define MERGE_H

#include "job/run.h"

/* Merge every part of j found under o->out_dir into the image and a sidecar whose stats sum the
   parts' (one per_process entry per part). 0 on success; 2 when parts are missing, of different
   splits, damaged or rendered from other inputs (nothing written, e says which); 1 when writing
   failed. */
int merge_parts(const struct job *j, const struct run_opts *o, struct run_result *rr, struct err *e);

#endif
