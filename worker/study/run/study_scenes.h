/* study_scenes: the scenes of one or more studies loaded once each (a suite's studies share a scene
   file's parse) and every estimate the cost model will be asked for announced to it, so that its
   pilots and set timings are shared: the one preparation of `--dry-run` and `worker plan`. */
#ifndef STUDY_SCENES_H
#define STUDY_SCENES_H

#include "base/err.h"
#include "job/cost_model.h"
#include "study/load/compare_model.h"

struct study_scenes {
    const struct study_scene **input; /* the study's parse each loaded scene came from */
    struct scene_file *sf;
    int n;
};

/* Load every scene of the n studies once into ss and tell m of every estimate to come (each
   seedless combination once, each settings reference's half). 0, or -1 with e filled; ss is then
   still freed by study_scenes_free. */
int study_scenes_prepare(struct compare *const *studies, int n, struct study_scenes *ss, struct cost_model *m,
                         struct err *e);

/* The loaded scene of study scene cs (NULL when it was not prepared). */
const struct scene_file *study_scenes_of(const struct study_scenes *ss, const struct compare_scene *cs);

void study_scenes_free(struct study_scenes *ss);

#endif
