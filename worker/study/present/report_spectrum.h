/* report_spectrum: each variant's radially averaged error power spectrum, as UTK shows point sets':
   power (over the image's mean power: white noise 1) against frequency (in units of Nyquist), the
   seeds' geometric mean with a +- one standard deviation band, at the point the error's look is
   judged at; one panel per scene. */
#ifndef REPORT_SPECTRUM_H
#define REPORT_SPECTRUM_H

#include "study/load/verdict_model.h"

/* The study's spectra as an SVG document (caller frees), or NULL when none was measured or on no
   memory. */
char *report_spectrum_svg(const struct verdict_study *s);

#endif
