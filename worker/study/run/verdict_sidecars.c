/* verdict_sidecars: what a compare output folder's sidecars add to its summary.csv. */
#include "verdict_sidecars.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/fileio.h"
#include "study/load/verdict_csv.h"

/* `"key": "value"` or `"key": number` from a sidecar's text, into out; 0 when absent. */
static int sidecar_field(const char *text, const char *key, char *out, size_t n)
{
    char pat[64];
    snprintf(pat, sizeof pat, "\"%s\": ", key);
    const char *p = text ? strstr(text, pat) : NULL;
    if (!p)
        return 0;
    p += strlen(pat);
    size_t k = 0, quoted = *p == '"';
    for (p += quoted; *p && k + 1 < n && (quoted ? *p != '"' : (*p != ',' && *p != '\n' && *p != '}')); p++)
        out[k++] = *p;
    out[k] = 0;
    return 1;
}

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

/* What the images' sidecars add: sampler, pool, non-finite samples and the reference. missing[s]:
   how many of scene s's sidecars are missing. */
void verdict_sidecars_read(struct compare *c, const char *dir, int *missing)
{
    for (int i = 0; i < c->n_items; i++) {
        struct compare_item *it = &c->items[i];
        if (!c->results.rows[i].done)
            continue;
        char path[JOB_PATH_MAX * 2], val[JOB_PATH_MAX];
        const char *dot = strrchr(it->job.output, '.');
        snprintf(path, sizeof path, "%s/%.*s.json", dir, dot ? (int)(dot - it->job.output) : JOB_NAME_MAX,
                 it->job.output);
        uint8_t *text = NULL;
        size_t len;
        struct err ignored;
        if (fileio_read_all(path, 1u << 20, &text, &len, &ignored) < 0) {
            missing[it->scene]++;
            continue;
        }
        const char *t = (const char *)text;
        double count;
        if (sidecar_field(t, "sampler", val, sizeof val))
            sampler_kind_parse(val, &it->job.spec.pixel.kind);
        double pool;
        if (sidecar_field(t, "poisson_pool", val, sizeof val) &&
            verdict_csv_figure(val, 0, (double)render_spec_find("poisson_pool")->hi, &pool) == 0)
            it->job.spec.poisson_pool = (int)pool; /* a job's range; anything else: unknown (0) */
        if (sidecar_field(t, "nonfinite_samples", val, sizeof val) ||
            sidecar_field(t, "nonfinite_dropped", val, sizeof val)) /* its name before issue 26 */
            c->results.rows[i].nonfinite =
                verdict_csv_figure(val, 0, 1e19, &count) == 0 ? (uint64_t)count : 0;
        struct compare_scene *cs = &c->scenes[it->scene];
        if (!cs->ref_path[0] && sidecar_field(t, "reference", val, sizeof val))
            find_reference(val, dir, cs->ref_path, sizeof cs->ref_path);
        free(text);
    }
}
