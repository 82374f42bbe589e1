/* verdict_model: freeing a verdict's arrays. */
#include "verdict_model.h"

#include <math.h>
#include <stdlib.h>

const struct verdict_entry *verdict_entry_of(const struct verdict_ranking *r, int v)
{
    for (int i = 0; i < r->n; i++)
        if (r->e[i].variant == v)
            return &r->e[i];
    return NULL;
}

const struct verdict_failure *verdict_failure_of(const struct verdict_scene *s, int v,
                                                 enum verdict_failure_kind kind)
{
    for (int i = 0; s && i < s->n_failures; i++)
        if (s->failures[i].variant == v && s->failures[i].kind == kind)
            return &s->failures[i];
    return NULL;
}

void verdict_look_free(struct verdict_look *l)
{
    free(l->point), free(l->mean), free(l->se), free(l->rel);
    free(l->by_relmse.e), free(l->by_look.e);
    *l = (struct verdict_look){.at = NAN};
}

void verdict_scene_free(struct verdict_scene *v)
{
    free(v->variants);
    free(v->by_samples.e);
    free(v->by_cpu.e);
    free(v->by_cpu.pair_p);
    free(v->point_rel), free(v->point_rel_lo), free(v->point_rel_hi);
    free(v->cost);
    free(v->by_slope.e);
    free(v->failures);
    free(v->spec), free(v->spec_lo), free(v->spec_hi), free(v->spec_peak_p), free(v->spec_aniso);
    free(v->repeat);
    free(v->repeat_bias);
    free(v->samples_vary);
    free(v->warnings);
    free(v->sentences);
    verdict_look_free(&v->look);
    *v = (struct verdict_scene){0};
}

void verdict_study_free(struct verdict_study *s)
{
    for (int i = 0; s->scenes && i < s->n_scenes; i++)
        verdict_scene_free(&s->scenes[i]);
    free(s->scenes);
    *s = (struct verdict_study){0};
}
