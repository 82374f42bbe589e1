/* compare_model: freeing a study and a suite. */
#include "compare_model.h"

#include <stdlib.h>

void compare_free(struct compare *c)
{
    if (!c)
        return;
    for (int s = 0; c->scenes && s < c->n_scenes; s++) {
        mask_free(c->scenes[s].mask);
        free(c->scenes[s].mask);
    }
    free(c->scenes);
    free(c->variants);
    free(c->points);
    free(c->seeds);
    free(c->items);
    study_results_free(&c->results);
    verdict_study_free(&c->verdict);
    if (c->owns_inputs)
        study_inputs_free(c->inputs);
    free(c);
}

void compare_suite_free(struct compare_suite *s)
{
    if (!s)
        return;
    for (int i = 0; i < s->n_studies; i++)
        compare_free(s->studies[i]);
    study_inputs_free(s->inputs);
    free(s);
}
