/* verdict_rank: the separation rule and the ranking built on it. Two variants are ranked apart
   when Welch's t test on their seeds' figures rejects equal means, Holm-corrected across every
   pair of the ranking, at VERDICT_ALPHA: the chance that a ranking separates any two variants
   that are in truth alike is at most about alpha, whatever the number of variants (docs/compare.md
   gives the measured rates). */
#ifndef VERDICT_RANK_H
#define VERDICT_RANK_H

#include "verdict_figures.h"

/* The family-wise error rate of a ranking: the chance of separating any two equal variants. */
#define VERDICT_ALPHA 0.05

/* Start an entry for variant v (its figures empty). */
void verdict_entry_start(struct verdict_entry *e, int v);

/* Add one seed's figure y to e: relMSE when log_scale (ranked on log y; y <= 0 or not finite is
   left out), a slope otherwise. */
void verdict_entry_add(struct verdict_entry *e, double y, int log_scale);

/* Finish e: value (relMSE: the geometric mean, exp of the mean log; else the mean), lo, hi (its
   95% confidence interval: Student's t on the mean, exp'd for relMSE; the value with one seed), mean and se
   (the ranked figure's mean and its standard error). NAN when no seed was added. */
void verdict_entry_end(struct verdict_entry *e, int log_scale);

/* Two-sided p-value of Welch's t test for equal means of a and b; 1 when either has fewer than
   two seeds, 0 or 1 when both have no spread (by whether their means differ). */
double verdict_welch_p(const struct verdict_entry *a, const struct verdict_entry *b);

/* Two-sided p-value of Student's t with df degrees of freedom (1 when df <= 0). */
double verdict_t_p(double t, double df);

/* Student's t 97.5% quantile with df degrees of freedom: a 95% interval is mean +- it x se. */
double verdict_t_975(double df);

/* Whether a is ranked ahead of b in r: a reaches the common point and b does not, or both do (or
   neither) and Holm's procedure over r's pairs separates them with a's mean lower. */
int verdict_beats(const struct verdict_ranking *r, const struct verdict_entry *a,
                  const struct verdict_entry *b);

/* Separate r's entries (filled by verdict_entry_end) pair by pair, set each rank to 1 + the number
   of variants ahead of it, order them best first (by rank, then mean) and set the status. */
void verdict_rank(struct verdict_ranking *r);

/* Figure i's relMSE with the reference's own noise (f->ref.relmse) taken out. */
double verdict_rel(const struct verdict_figures *f, int i);

/* The variants at rank 1 of r joined by " = ", then " (tie)" when tie_note and they tie; or
   "inconclusive". */
void verdict_ranking_winner(const struct verdict_scene *v, const struct verdict_ranking *r, int tie_note,
                            char *buf, size_t n);

#endif
