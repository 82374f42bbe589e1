/* verdict_out: a verdict as verdict.json, as the HTML that opens a report (with the plots of how
   the error looks, report_look.h), and as the summary and warnings on stderr. */
#ifndef VERDICT_OUT_H
#define VERDICT_OUT_H

#include <stddef.h>

#include "base/sbuf.h"
#include "study/load/study_env.h"
#include "study/judge/verdict.h"

/* verdict.json: {"job", "error", "alpha", "tie_rule", "reproducibility" (env's, when not NULL),
   "studies": [{"study", "scenes": [{"scene", "seeds", "reference_relmse", "equal_samples",
   "equal_cpu_time", "slopes", "failures", "warnings", "sentences"}]}]}. Malloc'd, NULL on no
   memory. */
char *verdict_json_text(const char *job, const struct verdict_study *s, int n, const struct study_env *env);

/* The verdict as HTML for the top of a report: per study and scene, the sentences, the three
   rankings with their figures and ties, the failures and the warnings; then the rule. */
void verdict_html(struct sbuf *b, const struct verdict_study *s, int n);

/* "seed-question: checker jitter, cornell inconclusive; soft-shadows: sobol" (equal CPU time),
   for the summary line on stderr. */
void verdict_summary(const struct verdict_study *s, int n, char *buf, size_t len);

/* Every warning of every scene, one line each ("soft-shadows: warning: checker: ..."), to stderr. */
void verdict_print_warnings(const struct verdict_study *s, int n);

#endif
