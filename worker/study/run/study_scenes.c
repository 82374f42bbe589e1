/* study_scenes: studies' scenes loaded once, the cost model's estimates announced. */
#include "study_scenes.h"

#include <stdlib.h>

#include "compare_ref.h"
#include "job/job_estimate.h"

const struct scene_file *study_scenes_of(const struct study_scenes *ss, const struct compare_scene *cs)
{
    for (int i = 0; i < ss->n; i++)
        if (ss->input[i] == cs->input)
            return &ss->sf[i];
    return NULL;
}

int study_scenes_prepare(struct compare *const *studies, int n, struct study_scenes *ss, struct cost_model *m,
                         struct err *e)
{
    int total = 0;
    for (int i = 0; i < n; i++)
        total += studies[i]->n_scenes;
    ss->input = calloc((size_t)total, sizeof *ss->input);
    ss->sf = calloc((size_t)total, sizeof *ss->sf);
    if (!ss->input || !ss->sf)
        return err_set(e, NULL, 0, 0, "out of memory");
    for (int i = 0; i < n; i++) {
        const struct compare *c = studies[i];
        for (int s = 0; s < c->n_scenes; s++) {
            if (study_scenes_of(ss, &c->scenes[s]))
                continue;
            ss->input[ss->n] = c->scenes[s].input;
            if (scene_load_src(&c->scenes[s].input->src, &ss->sf[ss->n++], e) < 0) /* as the study read it */
                return -1;
        }
        for (int k = 0; k < c->n_items; k++)
            if (c->items[k].seed == 0 &&
                job_estimate_expect(&c->items[k].job, study_scenes_of(ss, &c->scenes[c->items[k].scene]), m,
                                    e) < 0)
                return -1;
        for (int s = 0; s < c->n_scenes; s++) {
            struct job hj;
            if (c->scenes[s].ref_kind != COMPARE_REF_SETTINGS)
                continue;
            compare_ref_half_job(&c->scenes[s], 0, &hj);
            if (job_estimate_expect(&hj, study_scenes_of(ss, &c->scenes[s]), m, e) < 0)
                return -1;
        }
    }
    return 0;
}

void study_scenes_free(struct study_scenes *ss)
{
    for (int i = 0; ss->sf && i < ss->n; i++)
        scene_file_free(&ss->sf[i]);
    free(ss->sf);
    free(ss->input);
}
