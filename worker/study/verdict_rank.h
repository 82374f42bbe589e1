/* verdict_rank: the tie rule and the ranking built on it. */
#ifndef VERDICT_RANK_H
#define VERDICT_RANK_H

#include "verdict.h"

/* The tie rule: a beats b when a's mean is lower (better) and the gap exceeds the larger of the
   two variants' min-max ranges across seeds, both measured on logarithms when log_scale (relMSE,
   where a ratio is what counts). A variant that reaches the common point beats one that does not. */
int verdict_beats(const struct verdict_entry *a, const struct verdict_entry *b, int log_scale);

/* Rank entries (value, lo, hi filled) best first and set their ranks and the status. n_seeds < 2
   makes any ranking inconclusive. */
void verdict_rank(struct verdict_ranking *r, int n_seeds);

#endif
