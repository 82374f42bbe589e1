/* study_machines: mark the equal-CPU-time ranking of a study rendered on several CPU models. */
#include "study_machines.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "job/outdir.h"
#include "job/sidecar.h"

/* Add text to v's warnings. 0 or -1. */
static int add_warning(struct verdict_scene *v, const char *text)
{
    char(*w)[VERDICT_TEXT_MAX] = realloc(v->warnings, (size_t)(v->n_warnings + 1) * sizeof *w);
    if (!w)
        return -1;
    v->warnings = w;
    snprintf(w[v->n_warnings++], VERDICT_TEXT_MAX, "%s", text);
    return 0;
}

int study_machines_mark(struct compare *c, const char *out_dir, struct err *e)
{
    enum { MAX_MODELS = 8 };
    char models[MAX_MODELS][128];
    int n = 0, more = 0;
    for (int i = 0; i < c->n_items; i++) {
        struct outdir_files files;
        struct sidecar_info info;
        struct err ignored;
        outdir_files(&c->items[i].job, out_dir, &files);
        if (sidecar_read(files.sidecar, &info, &ignored) < 0 || !info.cpu_model[0])
            continue;
        int k = 0;
        while (k < n && strcmp(models[k], info.cpu_model))
            k++;
        if (k == n && n < MAX_MODELS)
            snprintf(models[n++], sizeof models[0], "%s", info.cpu_model);
        else if (k == n)
            more = 1;
    }
    c->verdict.machines[0] = 0;
    if (n < 2)
        return 0;
    size_t len = 0;
    for (int k = 0; k < n && len < sizeof c->verdict.machines; k++)
        len += (size_t)snprintf(c->verdict.machines + len, sizeof c->verdict.machines - len, "%s%s",
                                k ? "; " : "", models[k]);
    char text[VERDICT_TEXT_MAX];
    snprintf(
        text, sizeof text,
        "the images were rendered on %d%s CPU models: their own CPU seconds (summary.csv) do not compare; "
        "equal CPU time is ranked by the cost design, timed on the one machine that gathered the study",
        n, more ? "+" : "");
    for (int s = 0; s < c->verdict.n_scenes; s++)
        if (add_warning(&c->verdict.scenes[s], text) < 0) {
            err_set(e, NULL, 0, 0, "out of memory");
            return -1;
        }
    return 0;
}
