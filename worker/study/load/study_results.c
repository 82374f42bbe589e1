/* study_results: a study's table of figures, made and freed. */
#include "study_results.h"

#include <math.h>
#include <stdlib.h>

int study_results_init(struct study_results *r, int n, int n_scenes)
{
    *r = (struct study_results){.rows = calloc(n > 0 ? (size_t)n : 1, sizeof *r->rows),
                                .refs = calloc(n_scenes > 0 ? (size_t)n_scenes : 1, sizeof *r->refs)};
    for (int s = 0; r->refs && s < n_scenes; s++)
        r->refs[s].fig.relmse = r->refs[s].fig.radiance = r->refs[s].fig.radiance_se = NAN;
    return r->rows && r->refs ? 0 : -1;
}

void study_results_free(struct study_results *r)
{
    free(r->rows);
    free(r->refs);
    free(r->cost_s);
    *r = (struct study_results){0};
}
