/* entry: one entry of a study's plan rendered alone (a batch array's task). */
#include "entry.h"

#include <stdio.h>
#include <unistd.h>

#include "farm/queue_part.h"
#include "job/jobfile.h"

/* The reference of entry x's render ready, or its half's shared lock held (in *fd): 0, or 1 or 2
   with e filled. */
static int take_reference(struct study_fan *f, const struct spread_entry *x, const struct run_opts *o,
                          int *fd, struct err *e)
{
    const struct compare *c = study_fan_study(f, x->k);
    int s = x->kind == STUDY_FAN_REFERENCE ? x->index : c->items[x->index].scene;
    *fd = -1;
    if (!study_fan_has_reference(f, x->k, s))
        return 0;
    *fd = study_fan_ref_lock(f, x->k, s, o, x->kind == STUDY_FAN_REFERENCE, e);
    if (*fd < 0 && e->msg[0])
        return 2;
    if (x->kind == STUDY_FAN_REFERENCE)
        return 0;
    int rc = study_fan_render(f, x->k, STUDY_FAN_REFERENCE, s, o, e); /* the halves' tasks done: reused */
    if (*fd >= 0)
        close(*fd);
    *fd = -1;
    return rc;
}

int entry_main(const char *path, const char *name, const struct run_opts *o)
{
    struct jobfile jf;
    struct study_fan f = {0};
    struct spread_entry x;
    struct err e = {0};
    char msg[4096] = "";
    int rc = 2, fd = -1;
    if (jobfile_open(&jf, path, path, &e) < 0) {
    } else if (jf.kind == JOBFILE_PLAIN) {
        err_set(&e, path, 0, 0, "--entry: a plain job has no entries (it is one render: use --part I/N)");
    } else if (study_fan_load(&jf, &f, &e) < 0) {
    } else if (spread_plan_parse(name, &x) < 0 || x.k >= study_fan_studies(&f) ||
               x.index >= (x.kind == STUDY_FAN_REFERENCE ? study_fan_study(&f, x.k)->n_scenes
                                                         : study_fan_study(&f, x.k)->n_items)) {
        err_set(&e, path, 0, 0, "--entry: %s is no entry of this study (see worker plan %s)", name, path);
    } else if ((rc = take_reference(&f, &x, o, &fd, &e)) == 0) {
        rc = queue_part_render(&f, &x, o, msg, sizeof msg, &e);
    }
    if (fd >= 0)
        close(fd);
    if (rc != 0)
        err_format(&e, msg, sizeof msg);
    if (rc != 0 || !o->quiet)
        fprintf(stderr, "%s: %s\n", name, msg);
    study_fan_free(&f);
    jobfile_close(&jf);
    return rc;
}
