/* verdict_look: how each variant's error looks (error_lowfreq, errspec.h: the error's energy share
   within 1/8 Nyquist over white noise's; below 1 is bluer) and which variant's is bluest at equal
   relMSE. The rule: at the sparsest samples per pixel every variant has (each at its point nearest
   it, in log spp), the variants whose relMSE is not ranked behind the best there (Welch, Holm, as
   every ranking) are compared by their seeds' mean error_lowfreq with the same test; the bluest is
   the one alone at rank 1 of that comparison (docs/compare.md#how-the-error-looks). */
#ifndef VERDICT_LOOK_H
#define VERDICT_LOOK_H

#include "verdict_figures.h"

/* out->look from f (f->lowfreq may be NULL: nothing measured), plus a sentence in out when two or
   more variants are compared. 0, or -1 out of memory (out->look's arrays then freed). */
int verdict_look_compute(const struct verdict_figures *f, struct verdict_scene *out);

#endif
