/* verdict_sidecars: what a compare output folder's sidecars add to its summary.csv. */
#include "verdict_sidecars.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/fileio.h"
#include "job/sidecar.h"

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
void verdict_sidecars_read(const struct compare *c, struct study_results *r, const char *dir, int *missing)
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
