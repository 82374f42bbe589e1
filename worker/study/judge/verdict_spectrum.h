/* verdict_spectrum: structured error from the error's spectrum: each variant's radially averaged
   error power per sweep point (the report's plot), and the `structured` failure where the seeds'
   pooled spectrum has a peak no noise gives or a strong anisotropy (errspec.h's rules). */
#ifndef VERDICT_SPECTRUM_H
#define VERDICT_SPECTRUM_H

#include "verdict_figures.h"

/* Fill out's spec arrays from f and add a VERDICT_PATTERN failure per structured variant (at the
   point where its peak is least likely by chance). 0, or -1 (out of memory). */
int verdict_spectrum_compute(const struct verdict_figures *f, struct verdict_scene *out);

#endif
