/* job_path: the files a job names: paths relative to the job file, a scene: value's places, and a
   "did you mean" for a scene that is not there. */
#ifndef JOB_PATH_H
#define JOB_PATH_H

#include <stddef.h>

#include "job_types.h"

/* The folder of the file at path into out: "." for a bare name, "/" for one at the root. */
void job_path_dir(const char *path, char *out, size_t n);

/* rel relative to the folder of the file base (an absolute rel is kept) into out. */
void job_path_resolve(const char *base, const char *rel, char *out, size_t n);

/* Whether p is a regular file (following symbolic links). */
int job_path_is_file(const char *p);

/* Set j->scene_path from the scene: value val: a bare name (no '/', no extension) is NAME.yaml in
   the scenes/ folders job_path.c's bare_dirs lists, else val is relative to the job file. 0 when it
   is a file; -1 with j->scene_path the first place looked at and *tried listing the others. */
int job_path_scene(struct job *j, const char *val, char *tried, size_t n);

/* " (did you mean X?)" for a scene: value val that names no file (after job_path_scene), when a
   file near it exists where it was looked for (into buf); else "". */
const char *job_path_scene_hint(const struct job *j, const char *val, char *buf, size_t n);

#endif
