/* verdict_from: a finished compare job's verdict, its figures gathered from its items (samples,
   CPU seconds, relMSE, sampler share, non-finite samples per seed) and its images (the share of
   the error that repeats in every seed). */
#ifndef VERDICT_FROM_H
#define VERDICT_FROM_H

#include "study/load/compare_model.h"
#include "verdict.h"

/* The verdict of every scene of c (its plan and results), whose images are in dir; its study is
   named c->name. found (NULL: nothing): more than one CPU model is listed in out->machines and each
   scene warns that equal CPU time mixes them; what a folder read back lacked is each scene's
   warning. Writes out alone. 0, or -1 with e filled (an image unreadable, no memory). */
int verdict_from_compare(const struct compare *c, const char *dir, const struct verdict_found *found,
                         struct verdict_study *out, struct err *e);

#endif
