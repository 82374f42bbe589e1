/* study_results: a study's table of figures, made and freed. */
#include "study_results.h"

#include <stdlib.h>

int study_results_init(struct study_results *r, int n)
{
    *r = (struct study_results){.rows = calloc(n > 0 ? (size_t)n : 1, sizeof *r->rows)};
    return r->rows ? 0 : -1;
}

void study_results_free(struct study_results *r)
{
    free(r->rows);
    free(r->cost_s);
    *r = (struct study_results){0};
}
