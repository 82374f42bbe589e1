/* queue_inputs: the files a queued job reads stay where its queue put them: a scene or reference
   path that lies inside the queue directory as written, but leaves it through a symbolic link, is
   not read. */
#ifndef QUEUE_INPUTS_H
#define QUEUE_INPUTS_H

#include "base/err.h"
#include "job/job.h"

/* Check j's scene and reference against queue directory dir: a path inside dir as written
   (folders and ".." taken as text) must resolve (realpath) inside dir too. A path written outside
   dir (absolute, or through "..") is the job author's choice and passes. 0, or -1 with e at the
   key's line:col. */
int queue_inputs_check(const char *dir, const struct job *j, struct err *e);

#endif
