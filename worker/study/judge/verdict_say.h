/* verdict_say: a scene verdict's words: each failure's line, the warnings (guards) and the plain
   sentences a reader can act on, from its figures and rankings. Internal to verdict.c. */
#ifndef VERDICT_SAY_H
#define VERDICT_SAY_H

#include "verdict_figures.h"

/* A failure just found added to out (variant v, at point p, its value and detail) with its text. */
void verdict_say_failure(const struct verdict_figures *f, struct verdict_scene *out,
                         enum verdict_failure_kind kind, int v, int p, double value, double detail);

/* out->warnings: one seed, a reference with too few samples, rankings whose neighbours differ by
   less than their spread, figures read beyond the measured points. */
void verdict_say_warnings(const struct verdict_figures *f, struct verdict_scene *out);

/* out->sentences: the winner at equal CPU time and at equal samples, the slopes, and what each
   failure and Poisson's cost mean for a user. */
void verdict_say_sentences(const struct verdict_figures *f, struct verdict_scene *out);

#endif
