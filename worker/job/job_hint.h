/* job_hint: a "did you mean" for a scene file that is not there, among the files that are. */
#ifndef JOB_HINT_H
#define JOB_HINT_H

#include <stddef.h>

/* The entry of folder dir nearest to name (ystr_nearest's closeness) into out: with stems, among
   the *.yaml files by their stems (name is a bare scene name); else among all entries by their
   full names. At most JOB_HINT_MAX_ENTRIES entries are looked at. 1 when one is near, else 0
   and out is "". */
#define JOB_HINT_MAX_ENTRIES 4096
int job_hint_nearest(const char *dir, const char *name, int stems, char *out, size_t n);

#endif
