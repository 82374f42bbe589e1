/* verdict_sidecars: the images' sidecars read back for `worker verdict`: non-finite samples and the
   reference (the settings are summary.csv's own columns). */
#ifndef VERDICT_SIDECARS_H
#define VERDICT_SIDECARS_H

#include "compare.h"

/* Fill r's done rows (plan c's results) from their sidecars in dir, and each scene's reference path
   where a sidecar names one; missing[s]: how many of scene s's sidecars are missing or unreadable
   (added to). */
void verdict_sidecars_read(const struct compare *c, struct study_results *r, const char *dir, int *missing);

#endif
