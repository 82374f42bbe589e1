/* verdict_load: a compare output folder read back (its summary.csv as a plan and results, with
   what its sidecars, sidecar_read the one reader, and images add) and judged again. */
#include "verdict_load.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "compare_cost.h"
#include "compare_ref.h"
#include "study/judge/verdict_from.h"
#include "job/sidecar.h"
#include "study/load/study_table.h"

/* Where the reference named in a sidecar is now: as written (relative to where the job ran), else
   in the output root's .cache/ beside the study (dir/../.cache or dir/.cache). */
static void find_reference(const char *named, const char *dir, char *out, size_t n)
{
    const char *base = strrchr(named, '/');
    base = base ? base + 1 : named;
    snprintf(out, n, "%s", named);
    if (access(out, R_OK) == 0)
        return;
    snprintf(out, n, "%s/../.cache/%s", dir, base);
    if (access(out, R_OK) == 0)
        return;
    snprintf(out, n, "%s/.cache/%s", dir, base);
    if (access(out, R_OK) != 0)
        out[0] = 0;
}

/* What the images' sidecars add to summary.csv's rows (sidecar_read, the one reader of a sidecar):
   non-finite samples and the reference. missing[s]: how many of scene s's sidecars are missing or
   unreadable. */
static void read_sidecars(const struct compare *c, struct study_results *r, const char *dir, int *missing)
{
    for (int i = 0; i < c->n_items; i++) {
        const struct compare_item *it = &c->items[i];
        if (!r->rows[i].done)
            continue;
        char path[JOB_PATH_MAX * 2];
        const char *dot = strrchr(it->job.output, '.');
        snprintf(path, sizeof path, "%s/%.*s.json", dir, dot ? (int)(dot - it->job.output) : JOB_NAME_MAX,
                 it->job.output);
        struct sidecar_info *info = malloc(sizeof *info);
        struct err ignored;
        if (!info || sidecar_read(path, info, &ignored) < 0) {
            missing[it->scene]++;
            free(info);
            continue;
        }
        r->rows[i].nonfinite = info->nonfinite;
        struct study_ref_result *rr = &r->refs[it->scene];
        if (!rr->path[0] && info->reference[0])
            find_reference(info->reference, dir, rr->path, sizeof rr->path);
        free(info);
    }
}

/* Judge study si of t, whose images are in dir; a warning per scene names what was skipped or left
   out. 0, or -1 with e filled. */
static int judge(const struct study_table *t, int si, const char *dir, struct verdict_study *out,
                 struct err *e)
{
    int *unfigured;
    struct compare *c = study_table_study(t, si, &unfigured, e);
    int *missing = c ? calloc(2 * (size_t)c->n_scenes, sizeof *missing) : NULL, *unscored = missing;
    if (!c || !missing) {
        compare_free(c);
        free(unfigured);
        return c ? err_set(e, dir, 0, 0, "out of memory") : -1;
    }
    unscored += c->n_scenes;
    read_sidecars(c, &c->results, dir, missing);
    study_table_label_spp(c);
    for (int i = 0; i < c->n_items; i++) { /* a relmse that is no error ("nan", "-1"): left out, said */
        struct study_result *r = &c->results.rows[i];
        if (r->done && r->has_error && !(isfinite(r->error.relmse) && r->error.relmse >= 0)) {
            r->error.relmse = NAN;
            unscored[c->items[i].scene]++;
        }
    }
    for (int s = 0; s < c->n_scenes; s++)
        if (c->results.refs[s].path[0])
            compare_ref_measure(&c->scenes[s], &c->results.refs[s]);
    (void)compare_cost_read(c, &c->results, dir); /* absent: the images' own times, said so */
    struct verdict_found found = {.no_sidecar = missing, .no_relmse = unscored, .no_figures = unfigured};
    int rc = verdict_from_compare(c, dir, &found, out, e);
    free(missing); /* and unscored */
    free(unfigured);
    compare_free(c);
    return rc;
}

int verdict_load_dir(const char *dir, struct verdict_study **out, int *n, char *job, size_t job_n,
                     struct err *e)
{
    char path[JOB_PATH_MAX + 16];
    struct study_table t;
    int rc = -1;
    *out = NULL, *n = 0;
    size_t end = strlen(dir), start;
    while (end > 1 && dir[end - 1] == '/') /* "out/study/": its last name */
        end--;
    for (start = end; start > 0 && dir[start - 1] != '/'; start--)
        ;
    snprintf(job, job_n, "%.*s", (int)(end - start), dir + start);
    snprintf(path, sizeof path, "%s/summary.csv", dir);
    if (study_table_read(&t, path, job, e) < 0)
        return -1;
    *out = calloc((size_t)t.studies.n, sizeof **out);
    rc = *out ? 0 : err_set(e, path, 0, 0, "out of memory");
    for (int i = 0; rc == 0 && i < t.studies.n; i++) {
        char sdir[JOB_PATH_MAX * 2];
        if (t.has_study)
            snprintf(sdir, sizeof sdir, "%s/%.*s", dir, (int)t.studies.len[i], t.studies.s[i]);
        else
            snprintf(sdir, sizeof sdir, "%s", dir);
        rc = judge(&t, i, sdir, &(*out)[i], e);
        *n += rc == 0;
    }
    if (rc < 0) { /* nothing half judged is handed back */
        for (int i = 0; i < *n; i++)
            verdict_study_free(&(*out)[i]);
        free(*out);
        *out = NULL, *n = 0;
    }
    study_table_free(&t);
    return rc;
}
