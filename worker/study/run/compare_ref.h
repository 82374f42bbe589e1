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
int compare_ref_half_target(const struct compare *c, int s, int h, const struct run_opts *o, struct job *j);

/* Half h of scene s's reference rendered whole into the cache (or found there). 0, 1 or 2. */
int compare_ref_half_render(const struct compare *c, int s, int h, const struct run_opts *o, struct err *e);

/* Half h of scene s's reference, just merged from its row parts at its place in the cache, recorded
   there (its .key beside it) so that compare_ref_prepare reuses it. 0 or -1 with e filled. */
int compare_ref_half_merged(const struct compare *c, int s, int h, const struct run_opts *o, struct err *e);

/* Scene s's reference made ready to score against, into r->refs[s]: a settings one rendered into
   OUT/.cache/ or reused when the cache holds it (its path, pixels, time and noise), a given image
   as load read it. 0, 1 or 2 as compare_run. */
int compare_ref_prepare(const struct compare *c, int s, struct study_results *r, const struct run_opts *o,
                        struct err *e);

/* The noise of the settings reference at rr->path measured again from its halves beside it
   (<stem>-a.exr, -b.exr), over cs's mask: rr's relmse, radiance, radiance_se (NAN without them)
   and spp (their sidecars'; 0 without). For a finished study re-judged. */
void compare_ref_measure(const struct compare_scene *cs, struct study_ref_result *rr);

/* Two parts of the summary line of studies cs[0..n) (a suite's when suite), from their results:
   refs, what their references were ("references: 2 rendered, 1 reused from cache (saving 3.1 s)",
   "reference image given", "no reference"; a reference an earlier study of the run rendered counts
   as reused), and resumed, how many images were current (", 4 of them current ...", or ""). */
void compare_ref_summary(const struct compare *const *cs, int n, int suite, char *refs, size_t refs_n,
                         char *resumed, size_t resumed_n);

#endif
