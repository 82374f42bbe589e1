/* compare_ref: a compare job's per-scene reference renders, cached under OUT/.cache/ by a key
   over everything that changes their pixels (scene bytes, settings, the worker program). */
#ifndef COMPARE_REF_H
#define COMPARE_REF_H

#include "compare.h"

/* Render scene s's reference into OUT/.cache/, or reuse it when the cache holds one. */
int compare_ref_prepare(struct compare *c, int s, const struct run_opts *o, struct err *e);

#endif
