/* queue_part: one entry of a study spread over a queue rendered: a reference's half or an image,
   whole, or one of its row parts (spread_plan.h); the worker that finds every part of a render
   present merges them (farm/merge.h) into its image and sidecar, once, under a lock beside them. */
#ifndef QUEUE_PART_H
#define QUEUE_PART_H

#include <stddef.h>

#include "spread_plan.h"

/* Render entry x of the study f (loaded) with the options o (a queue's: DIR/done). Returns 0, 1
   (render or write failed, retry) or 2 (bad input) with e filled; what was done in msg (n bytes):
   rendered, current, and merged or not. */
int queue_part_render(struct study_fan *f, const struct spread_entry *x, const struct run_opts *o, char *msg,
                      size_t n, struct err *e);

#endif
