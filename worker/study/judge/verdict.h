/* verdict: what a compare job's figures conclude, per study and scene: the ranking at equal
   samples, at equal CPU time and by slope, with ties where variants differ by less than their
   seeds' spread; the failure modes found; guards; and plain sentences. Pure arithmetic on the
   figures (verdict_from.c gathers them from a finished compare job), so the rules are testable on
   constructed figures. */
#ifndef VERDICT_H
#define VERDICT_H

#include "base/err.h"
#include "study/load/verdict_model.h"
#include "verdict_figures.h"

/* Whether a sweep whose points' mean samples per pixel run from lo to hi changes the samples (by
   more than VERDICT_SAMPLES_VARY): a slope and "stops falling" need it to. */
int verdict_samples_vary(double lo, double hi);

/* The verdict of one scene from its figures. 0, or -1 with e filled (out of memory). */
int verdict_scene_compute(const struct verdict_figures *f, struct verdict_scene *out, struct err *e);

#endif
