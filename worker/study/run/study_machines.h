/* study_machines: the machines a compare job's images were rendered on (their sidecars' host and
   cpu_model), and the mark on the equal-CPU-time ranking when their CPU models differ: CPU seconds
   of different machines do not compare, while the equal-samples and slope rankings do not depend
   on the machine. */
#ifndef STUDY_MACHINES_H
#define STUDY_MACHINES_H

#include "study/load/compare_model.h"

/* Read the sidecars of c's images under out_dir; when they name more than one CPU model, record
   them in c->verdict.machines and add a warning to each scene's verdict (report and verdict.json).
   0, or -1 with e filled (out of memory). A missing or older sidecar counts as no model. */
int study_machines_mark(struct compare *c, const char *out_dir, struct err *e);

#endif
