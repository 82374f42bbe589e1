/* report_look: a study's plots of how its error looks, one panel per scene, a line per variant:
   error_lowfreq against relMSE along the sweep (mean over seeds, whiskers +- one standard error),
   or the radially averaged error power spectrum as UTK shows point sets' (power over the image's
   mean power, white noise 1, against frequency in units of Nyquist; the seeds' geometric mean with
   a +- one standard deviation band) at the point the error's look is judged at. */
#ifndef REPORT_LOOK_H
#define REPORT_LOOK_H

#include "study/load/verdict_model.h"

enum report_look { REPORT_LOOK_LOWFREQ, REPORT_LOOK_SPECTRUM };

/* The study's plot as an SVG document (caller frees); NULL on no memory, and for the spectra when
   none was measured. */
char *report_look_svg(const struct verdict_study *s, enum report_look plot);

#endif
