/* compare_ref: a compare job's per-scene reference renders, cached under OUT/.cache/ by a key
   over everything that changes their pixels (scene bytes, settings, the worker program). */
#ifndef COMPARE_REF_H
#define COMPARE_REF_H

#include "compare.h"

/* Half h (0 or 1) of scene cs's settings reference as it is rendered: cs->ref_job with half the
   samples (each threshold, a spacing, times sqrt 2, at most 100) and its own seed. The reference's
   samples per pixel are its two halves' together (what --dry-run estimates). */
void compare_ref_half_job(const struct compare_scene *cs, int h, struct job *j);

/* Render scene s's reference into OUT/.cache/, or reuse it when the cache holds one. */
int compare_ref_prepare(struct compare *c, int s, const struct run_opts *o, struct err *e);

/* The noise of the settings reference at cs->ref_path measured again from its halves beside it
   (<stem>-a.exr, -b.exr): ref_relmse, ref_radiance, ref_radiance_se (NAN without them) and
   ref_spp (their sidecars'; 0 without). For a finished study re-judged. */
void compare_ref_measure(struct compare_scene *cs);

#endif
