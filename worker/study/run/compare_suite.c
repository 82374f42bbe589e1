/* compare_suite: running a loaded suite: each study as a compare job into OUT/<suite>/<study>/,
   then the suite's verdict.json, summary.csv, chart.svg and report.html, and its summary line. */
#include "compare_suite.h"
#include "compare.h"
#include "compare_ref.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fileio.h"
#include "base/sbuf.h"
#include "study/present/compare_suite_out.h"
#include "job/outdir.h"
#include "job/run_out.h"
#include "study/present/verdict_out.h"

/* The studies' verdicts side by side, as verdict.h's calls take them: shallow copies (each
   study's compare owns its verdict's arrays); a study without one has no scenes. Free the array
   alone. NULL on no memory. */
static struct verdict_study *suite_verdicts(const struct compare_suite *s)
{
    struct verdict_study *v = calloc((size_t)s->n_studies, sizeof *v);
    for (int i = 0; v && i < s->n_studies; i++)
        if (s->studies[i]->has_verdict)
            v[i] = s->studies[i]->verdict;
        else
            snprintf(v[i].name, sizeof v[i].name, "%s", s->studies[i]->name);
    return v;
}

/* The suite's own files, under the folder's lock as compare_run writes a study's. 0 or -1. */
static int write_top(const struct compare_suite *s, const char *dir, const struct run_opts *o, struct err *e)
{
    char paths[4][2100];
    const char *files[] = {"verdict.json", "summary.csv", "chart.svg", "report.html"};
    const char *outs[5] = {NULL};
    for (int i = 0; i < 4; i++) {
        snprintf(paths[i], sizeof paths[i], "%s/%s", dir, files[i]);
        outs[i] = paths[i];
    }
    struct verdict_study *v = suite_verdicts(s);
    int lock = -1, rc = -1;
    e->msg[0] = 0;
    if (!v)
        return err_set(e, NULL, 0, 0, "out of memory");
    if (outdir_mkdirs(dir, NULL, e) == 0 && run_out_lock_outputs(dir, outs, o, &lock, e) == 0 &&
        fileio_write_text(dir, "verdict.json",
                          verdict_json_text(s->name, v, s->n_studies, &s->studies[0]->env), e) == 0 &&
        fileio_write_text(dir, "summary.csv", compare_suite_csv(s, dir, e), e) == 0 &&
        fileio_write_text(dir, "chart.svg", compare_suite_chart_svg(s), e) == 0 &&
        fileio_write_text(dir, "report.html", compare_suite_report_html(s, v, e), e) == 0)
        rc = 0;
    outdir_unlock(lock);
    free(v);
    return rc;
}

int compare_suite_run(struct compare_suite *s, const struct run_opts *o, struct err *e)
{
    char dir[2048];
    outdir_dir(o->out_dir, s->name, dir, sizeof dir);
    if (outdir_check(dir, e) < 0)
        return 2;
    struct run_opts in_suite = *o; /* each study as if run alone with --out OUT/<suite> */
    in_suite.out_dir = dir;
    for (int i = 0; i < s->n_studies; i++) {
        struct compare *c = s->studies[i];
        run_say(o, "study %d/%d: %s\n", i + 1, s->n_studies, c->name);
        int rc = compare_run(c, &in_suite, e);
        if (rc == 1) /* a render failure names its study; bad input names its file */
            err_prefix(e, c->name);
        if (rc != 0)
            return rc;
    }
    return write_top(s, dir, o, e) < 0 ? 1 : 0;
}

/* "compare: 480 images in 4 studies (seed-question 120, ...), references: ..., 41.2 s -> out/compare/;
   at equal CPU time: seed-question: checker jitter, ..." */
void compare_suite_summary_line(const struct compare_suite *s, double wall_s, const char *out_dir, char *buf,
                                size_t n)
{
    char studies[1024] = "", refs[160], resumed[96], verdict[1024] = "";
    for (int i = 0; i < s->n_studies; i++) {
        size_t used = strlen(studies);
        snprintf(studies + used, sizeof studies - used, "%s%s %d", i ? ", " : "", s->studies[i]->name,
                 s->studies[i]->n_items);
    }
    compare_ref_summary((const struct compare *const *)s->studies, s->n_studies, 1, refs, sizeof refs,
                        resumed, sizeof resumed);
    struct verdict_study *v = suite_verdicts(s);
    if (v)
        verdict_summary(v, s->n_studies, verdict, sizeof verdict);
    free(v);
    snprintf(buf, n, "%s: %d image%s in %d stud%s (%s)%s, %s, %.2f s -> %s/%s/; at equal CPU time: %s",
             s->name, s->n_items, sbuf_plural(s->n_items), s->n_studies, s->n_studies == 1 ? "y" : "ies",
             studies, resumed, refs, wall_s, outdir_root(out_dir), s->name,
             verdict[0] ? verdict : "no verdict");
}
