/* entry: `worker STUDY.yaml --entry NAME --out OUT`: one entry of `worker plan`'s rendered as a
   queue's worker renders it, for a batch system's array of one task per entry. */
#ifndef ENTRY_H
#define ENTRY_H

#include "job/run.h"

/* Render entry `name` of the compare job or suite at path into o->out_dir: a reference's half under
   its reference's shared lock, an image once its scene's reference is prepared under that lock
   taken exclusive. One line on stderr; the exit status 0, 1 or 2. */
int entry_main(const char *path, const char *name, const struct run_opts *o);

#endif
