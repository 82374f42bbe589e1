/* study_fan: one render of a compare job or suite at a time. */
#include "study_fan.h"

#include <stdio.h>

#include "compare_ref.h"
#include "job/outdir.h"

int study_fan_load(const char *from, const char *path, struct study_fan *f, struct err *e)
{
    f->c = NULL;
    f->s = NULL;
    if (compare_suite_is_suite(from))
        f->s = compare_suite_load_as(from, path, e);
    else
        f->c = compare_load_as(from, path, e);
    return f->c || f->s ? 0 : -1;
}

void study_fan_free(struct study_fan *f)
{
    compare_suite_free(f->s);
    compare_free(f->c);
    f->s = NULL;
    f->c = NULL;
}

const char *study_fan_name(const struct study_fan *f)
{
    return f->s ? f->s->name : f->c->name;
}

int study_fan_studies(const struct study_fan *f)
{
    return f->s ? f->s->n_studies : 1;
}

struct compare *study_fan_study(const struct study_fan *f, int k)
{
    return f->s ? f->s->studies[k] : f->c;
}

int study_fan_has_reference(const struct study_fan *f, int k, int s)
{
    return study_fan_study(f, k)->scenes[s].ref_kind == COMPARE_REF_SETTINGS;
}

int study_fan_render(struct study_fan *f, int k, enum study_fan_kind kind, int index,
                     const struct run_opts *o, struct err *e)
{
    if (k < 0 || k >= study_fan_studies(f)) {
        err_set(e, NULL, 0, 0, "%s: no study %d", study_fan_name(f), k);
        return 2;
    }
    struct compare *c = study_fan_study(f, k);
    int count = kind == STUDY_FAN_REFERENCE ? c->n_scenes : c->n_items;
    if (index < 0 || index >= count) {
        err_set(e, NULL, 0, 0, "%s: no %s %d in study %d", study_fan_name(f),
                kind == STUDY_FAN_REFERENCE ? "reference" : "image", index, k);
        return 2;
    }
    char dir[2048];
    struct run_opts in = *o; /* a suite's study renders as compare_suite_run has it: --out OUT/<suite> */
    if (f->s) {
        outdir_dir(o->out_dir, f->s->name, dir, sizeof dir);
        in.out_dir = dir;
    }
    int rc = kind == STUDY_FAN_REFERENCE ? compare_ref_prepare(c, index, &in, e)
                                         : compare_run_item(c, index, &in, e);
    if (rc == 1)
        err_prefix(e, c->name);
    return rc;
}
