/* jobfile_run: a plain job through run_job, a compare job or suite through the study. */
#include "jobfile_run.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

#include "base/clock.h"
#include "base/sbuf.h"
#include "compare.h"
#include "compare_suite.h"
#include "study_fan.h"

/* A compare job (c) or a suite (s), loaded from the parsed job file, run, and its line printed. */
static int run_study(const struct jobfile *f, const struct run_opts *o,
                     int (*name_ok)(const char *name, void *arg), void *arg, struct jobfile_outcome *out)
{
    struct study_fan fan; /* one of c and s */
    double t0 = clock_s(CLOCK_MONOTONIC);
    int rc = 2;
    const char *name = study_fan_load(f, &fan, &out->e) == 0 ? study_fan_name(&fan) : NULL;
    struct compare *c = fan.c;
    struct compare_suite *s = fan.s;
    if (name)
        snprintf(out->name, sizeof out->name, "%s", name);
    if (name && name_ok && !name_ok(name, arg))
        goto done;
    if (name)
        rc = s ? compare_suite_run(s, o, &out->e) : compare_run(c, o, &out->e);
    if (rc != 0) {
        if (rc == 1 && name) /* a render failure names the job; bad input names its file */
            err_prefix(&out->e, name);
        err_format(&out->e, out->line, sizeof out->line);
    } else if (s) { /* each study's verdict warnings were printed as it finished (compare_run) */
        compare_suite_summary_line(s, clock_s(CLOCK_MONOTONIC) - t0, o->out_dir, out->line, sizeof out->line);
    } else {
        compare_summary_line(c, clock_s(CLOCK_MONOTONIC) - t0, o->out_dir, out->line, sizeof out->line);
    }
    if (!(rc == 1 && o->stop && *o->stop)) { /* stopped (a signal, a queue claim gone): the caller says so */
        struct sbuf shown = {0};             /* the names in it as the terminal sanitiser shows them */
        sbuf_shown(&shown, out->line);
        if (shown.buf)
            fprintf(stderr, "%s\n", shown.buf);
        sbuf_free(&shown);
    }
done:
    study_fan_free(&fan);
    return rc;
}

int jobfile_run(const struct jobfile *f, const struct run_opts *o,
                int (*name_ok)(const char *name, void *arg), void *arg, struct jobfile_outcome *out)
{
    memset(out, 0, sizeof *out);
    if (f->kind != JOBFILE_PLAIN)
        return run_study(f, o, name_ok, arg, out);
    snprintf(out->name, sizeof out->name, "%s", f->job.name);
    if (name_ok && !name_ok(f->job.name, arg))
        return 2;
    struct run_opts with_scene = *o;
    with_scene.scene = &f->scene;
    with_scene.ref_bytes = f->ref_bytes;
    with_scene.ref_len = f->ref_len;
    return run_job(&f->job, &with_scene, &out->rr, &out->e);
}
