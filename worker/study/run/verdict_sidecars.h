/* verdict_sidecars: the images' sidecars read back for `worker verdict`: non-finite samples and the
   reference (the settings are summary.csv's own columns). */
#ifndef VERDICT_SIDECARS_H
#define VERDICT_SIDECARS_H

#include "compare.h"

/* Fill c's done items from their sidecars in dir; missing[s]: how many of scene s's sidecars are
   missing or unreadable (added to). */
void verdict_sidecars_read(struct compare *c, const char *dir, int *missing);

#endif
