/* study_machines: the CPU models a compare job's images were rendered on (their sidecars'
   cpu_model), for the verdict to mark its equal-CPU-time ranking when they differ
   (verdict_from_compare). */
#ifndef STUDY_MACHINES_H
#define STUDY_MACHINES_H

#include "study/load/compare_model.h"

/* The CPU models of c's images, read from their sidecars under out_dir, into out's machines (the
   first STUDY_MACHINES_MAX listed; out emptied first); a missing or older sidecar counts as none. */
#define STUDY_MACHINES_MAX 8
void study_machines_read(const struct compare *c, const char *out_dir, struct verdict_found *out);

#endif
