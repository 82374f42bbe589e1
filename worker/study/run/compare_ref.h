/* compare_ref: a compare job's per-scene reference renders, cached under OUT/.cache/ by a key
   over everything that changes their pixels (scene bytes, settings, the worker program). */
#ifndef COMPARE_REF_H
#define COMPARE_REF_H

#include "job/run.h"
#include "study/load/compare_model.h"

/* Half h (0 or 1) of scene cs's settings reference as it is rendered: cs->ref_job with half the
   samples (each threshold, a spacing, times sqrt 2, at most 100) and its own seed. The reference's
   samples per pixel are its two halves' together (what --dry-run estimates). */
void compare_ref_half_job(const struct compare_scene *cs, int h, struct job *j);

/* Half h of scene s's settings reference as compare_ref_prepare renders it into OUT/.cache/: its
   job (*j, its hash the reference's cache key, so that its row parts are matched by it); 1 when the
   cache holds it already (nothing to render), else 0. */
int compare_ref_half_target(struct compare *c, int s, int h, const struct run_opts *o, struct job *j);

/* Half h of scene s's reference rendered whole into the cache (or found there). 0, 1 or 2. */
int compare_ref_half_render(struct compare *c, int s, int h, const struct run_opts *o, struct err *e);

/* Half h of scene s's reference, just merged from its row parts at its place in the cache, recorded
   there (its .key beside it) so that compare_ref_prepare reuses it. 0 or -1 with e filled. */
int compare_ref_half_merged(struct compare *c, int s, int h, const struct run_opts *o, struct err *e);

/* Render scene s's reference into OUT/.cache/, or reuse it when the cache holds one. */
int compare_ref_prepare(struct compare *c, int s, const struct run_opts *o, struct err *e);

/* The noise of the settings reference at cs->ref_path measured again from its halves beside it
   (<stem>-a.exr, -b.exr): ref_relmse, ref_radiance, ref_radiance_se (NAN without them) and
   ref_spp (their sidecars'; 0 without). For a finished study re-judged. */
void compare_ref_measure(struct compare_scene *cs);

#endif
