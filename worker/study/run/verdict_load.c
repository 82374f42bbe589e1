/* verdict_load: a compare output folder's summary.csv, sidecars and images back into a struct
   compare, judged again. */
#include "verdict_load.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/fileio.h"
#include "compare.h"
#include "compare_cost.h"
#include "compare_ref.h"
#include "study/judge/verdict_from.h"

#define CSV_MAX_BYTES (64u << 20)
#define CSV_FIELDS 20
/* Most rows read: a suite of up to 64 studies of COMPARE_MAX_ITEMS images each (the work below
   grows with their square per study). */
#define CSV_MAX_ROWS (64 * COMPARE_MAX_ITEMS)
#define KEY_MAX 512

/* summary.csv parsed: rows of field pointers into one buffer of unquoted, NUL-ended fields. */
struct csv {
    char *text;
    char *(*rows)[CSV_FIELDS];
    int n_rows, n_fields; /* n_fields: the header's; row 0 is the header */
};

/* The columns read, by name (study is optional: a suite's). */
enum {
    C_STUDY,
    C_SCENE,
    C_VARIANT,
    C_THRESHOLD,
    C_LT,
    C_SEED,
    C_SPP,
    C_WALL,
    C_CPU,
    C_SHARE,
    C_RELMSE,
    C_DOMAIN,
    C_IMAGE,
    C_LOWFREQ, /* optional: a summary.csv from before it was written has none */
    N_COLS
};
static const char *const col_names[N_COLS] = {
    "study",  "scene", "variant",       "threshold", "light_threshold", "seed",  "samples_per_pixel_mean",
    "wall_s", "cpu_s", "sampler_share", "relmse",    "domain",          "image", "error_lowfreq"};

/* Parse RFC 4180 text in place: a quoted field's "" is one quote. -1 on a row of another width. */
static int csv_parse(struct csv *t, char *text, size_t len, const char *path, struct err *e)
{
    size_t lines = 1;
    for (size_t i = 0; i < len; i++)
        lines += text[i] == '\n' || text[i] == '\r'; /* a row ends at either (CR alone too) */
    t->text = text;
    t->rows = calloc(lines, sizeof *t->rows);
    if (!t->rows)
        return err_set(e, path, 0, 0, "out of memory");
    char *r = text, *w = text;
    while (*r) {
        int nf = 0;
        for (;;) {
            char *start = w;
            if (*r == '"') {
                for (r++; *r && !(*r == '"' && r[1] != '"'); r++)
                    *w++ = *r == '"' ? *r++ : *r;
                r += *r == '"';
            } else
                while (*r && *r != ',' && *r != '\n' && *r != '\r')
                    *w++ = *r++;
            char end = *r;
            *w++ = 0;
            if (nf < CSV_FIELDS)
                t->rows[t->n_rows][nf] = start;
            nf++;
            r += end != 0;
            if (end != ',') {
                r += end == '\r' && *r == '\n';
                break;
            }
        }
        if (t->n_rows == 0)
            t->n_fields = nf;
        if (t->n_rows > CSV_MAX_ROWS)
            return err_set(e, path, t->n_rows + 1, 0, "more than %d rows", CSV_MAX_ROWS);
        if (nf != t->n_fields || nf > CSV_FIELDS)
            return err_set(e, path, t->n_rows + 1, 0, "%d fields, the header has %d", nf, t->n_fields);
        t->n_rows++;
    }
    return 0;
}

/* Index of s in list (n entries of COMPARE_LABEL_MAX), appended when absent. */
static int intern(char (*list)[COMPARE_LABEL_MAX], int *n, const char *s)
{
    for (int i = 0; i < *n; i++)
        if (!strcmp(list[i], s))
            return i;
    snprintf(list[*n], COMPARE_LABEL_MAX, "%s", s);
    return (*n)++;
}

/* A point's key: its image name without "-s<seed>.<ext>" (what the sweep adds: -t20-lt10-pool64). */
static void point_key(const char *image, char *key, size_t n)
{
    snprintf(key, n, "%s", image);
    char *s = strrchr(key, '-');
    if (s && s[1] == 's')
        *s = 0;
}

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
static void read_sidecars(struct compare *c, const char *dir, int *missing)
{
    for (int i = 0; i < c->n_items; i++) {
        struct compare_item *it = &c->items[i];
        if (!it->done)
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
        if (sidecar_field(t, "sampler", val, sizeof val))
            sampler_kind_parse(val, &it->job.sampler);
        if (sidecar_field(t, "poisson_pool", val, sizeof val))
            it->job.poisson_pool = atoi(val);
        if (sidecar_field(t, "nonfinite_samples", val, sizeof val) ||
            sidecar_field(t, "nonfinite_dropped", val, sizeof val)) /* its name before issue 26 */
            it->nonfinite = strtoull(val, NULL, 10);
        struct compare_scene *cs = &c->scenes[it->scene];
        if (!cs->ref_path[0] && sidecar_field(t, "reference", val, sizeof val))
            find_reference(val, dir, cs->ref_path, sizeof cs->ref_path);
        free(text);
    }
}

/* One study's rows (those whose study column is `study`, or all) into a struct compare. */
static struct compare *build(const struct csv *t, const int *col, const char *study, const char *dir,
                             struct err *e)
{
    struct compare *c = calloc(1, sizeof *c);
    int n = t->n_rows - 1, cap = n > 0 ? n : 1;
    char(*keys)[COMPARE_LABEL_MAX] = calloc((size_t)cap, sizeof *keys);
    char(*scenes)[COMPARE_LABEL_MAX] = calloc((size_t)cap, sizeof *scenes);
    int *rows = calloc((size_t)cap * 4, sizeof *rows), n_keys = 0, m = 0;
    if (c) {
        c->variants = calloc((size_t)cap, sizeof *c->variants),
        c->points = calloc((size_t)cap, sizeof *c->points);
        c->seeds = calloc((size_t)cap, sizeof *c->seeds);
    }
    if (!c || !keys || !scenes || !rows || !c->variants || !c->points || !c->seeds) {
        err_set(e, dir, 0, 0, "out of memory");
        goto fail;
    }
    snprintf(c->name, sizeof c->name, "%s", study);
    char(*seeds)[COMPARE_LABEL_MAX] = keys; /* seeds interned first, keys after (below) */
    for (int r = 1; r <= n; r++) {
        char *const *f = t->rows[r];
        if (col[C_STUDY] >= 0 && strcmp(f[col[C_STUDY]], study))
            continue;
        int *x = &rows[4 * m++];
        x[0] = r, x[1] = intern(scenes, &c->n_scenes, f[col[C_SCENE]]);
        x[2] = intern(c->variants, &c->n_variants, f[col[C_VARIANT]]);
        x[3] = intern(seeds, &c->n_seeds, f[col[C_SEED]]);
    }
    if (m > COMPARE_MAX_ITEMS) {
        err_set(e, dir, 0, 0, "summary.csv: study %s has %d rows, more than a compare job's %d", study, m,
                COMPARE_MAX_ITEMS);
        goto fail;
    }
    for (int k = 0; k < c->n_seeds; k++)
        c->seeds[k] = strtoull(seeds[k], NULL, 10);
    /* points: each (scene, variant)'s keys in order; labelled by the first variant's thresholds */
    int *point = calloc((size_t)(m ? m : 1), sizeof *point);
    if (!point) {
        err_set(e, dir, 0, 0, "out of memory");
        goto fail;
    }
    for (int i = 0; i < m; i++) {
        char key[KEY_MAX];
        point_key(t->rows[rows[4 * i]][col[C_IMAGE]], key, sizeof key);
        int p = 0, seen = 0;
        for (int j = 0; j < i && !seen; j++) { /* the same key earlier: its point */
            char other[KEY_MAX];
            point_key(t->rows[rows[4 * j]][col[C_IMAGE]], other, sizeof other);
            if (!strcmp(other, key))
                p = point[j], seen = 1;
        }
        if (!seen) /* a new key of this (scene, variant): the next point */
            for (int j = 0; j < i; j++)
                if (rows[4 * j + 1] == rows[4 * i + 1] && rows[4 * j + 2] == rows[4 * i + 2])
                    p = point[j] + 1 > p ? point[j] + 1 : p;
        point[i] = p;
        if (p >= c->n_points) {
            c->n_points = p + 1;
            const char *const *f = (const char *const *)t->rows[rows[4 * i]];
            snprintf(c->points[p], COMPARE_LABEL_MAX, "threshold %s, light_threshold %s", f[col[C_THRESHOLD]],
                     f[col[C_LT]]);
        }
    }
    /* light_threshold named only when the points differ in it */
    const char *lt = c->n_points ? strstr(c->points[0], ", light_threshold") : NULL;
    int same = lt != NULL;
    for (int p = 1; same && p < c->n_points; p++)
        same = strstr(c->points[p], lt) != NULL;
    for (int p = 0; same && p < c->n_points; p++)
        *strstr(c->points[p], ", light_threshold") = 0;
    n_keys = c->n_scenes * c->n_variants * c->n_points * c->n_seeds;
    c->n_items = n_keys;
    c->scenes = calloc((size_t)(c->n_scenes ? c->n_scenes : 1), sizeof *c->scenes);
    c->items = calloc((size_t)(n_keys ? n_keys : 1), sizeof *c->items);
    if (!c->scenes || !c->items || m == 0) {
        free(point);
        err_set(e, dir, 0, 0, m ? "out of memory" : "summary.csv: no rows for study %s", study);
        goto fail;
    }
    for (int s = 0; s < c->n_scenes; s++) {
        snprintf(c->scenes[s].name, sizeof c->scenes[s].name, "%s", scenes[s]);
        c->scenes[s].ref_domain = IMG_DISPLAY8;
    }
    for (int i = 0; i < m; i++) {
        char *const *f = t->rows[rows[4 * i]];
        int s = rows[4 * i + 1], v = rows[4 * i + 2], k = rows[4 * i + 3];
        struct compare_item *it = &c->items[compare_index(c, s, v, point[i], k)];
        *it = (struct compare_item){.scene = s, .variant = v, .point = point[i], .seed = k, .done = 1};
        snprintf(it->job.output, sizeof it->job.output, "%s", f[col[C_IMAGE]]);
        it->spp_mean = atof(f[col[C_SPP]]), it->wall_s = atof(f[col[C_WALL]]);
        it->cpu_s = atof(f[col[C_CPU]]), it->sampler_share = atof(f[col[C_SHARE]]);
        it->has_error = f[col[C_RELMSE]][0] != 0;
        it->error.relmse = it->has_error ? atof(f[col[C_RELMSE]]) : NAN;
        it->error_lowfreq = col[C_LOWFREQ] >= 0 && f[col[C_LOWFREQ]][0] ? atof(f[col[C_LOWFREQ]]) : NAN;
        if (it->has_error) {
            c->scenes[s].ref_kind = COMPARE_REF_SETTINGS;
            if (!strcmp(f[col[C_DOMAIN]], "linear"))
                c->scenes[s].ref_domain = IMG_LINEAR;
        }
    }
    free(point);
    free(keys), free(scenes), free(rows);
    return c;
fail:
    free(keys), free(scenes), free(rows);
    compare_free(c);
    return NULL;
}

/* Judge one study in dir; a warning per scene names the checks skipped for missing sidecars. */
static int judge(const struct csv *t, const int *col, const char *study, const char *dir,
                 struct verdict_study *out, struct err *e)
{
    struct compare *c = build(t, col, study, dir, e);
    if (!c)
        return -1;
    int *missing = calloc(2 * (size_t)c->n_scenes, sizeof *missing);
    if (!missing) {
        compare_free(c);
        return err_set(e, dir, 0, 0, "out of memory");
    }
    int *unscored = missing + c->n_scenes;
    read_sidecars(c, dir, missing);
    for (int i = 0; i < c->n_items; i++) { /* a relmse that is no error ("nan", "-1"): left out, said */
        struct compare_item *it = &c->items[i];
        if (it->done && it->has_error && !(isfinite(it->error.relmse) && it->error.relmse >= 0)) {
            it->error.relmse = NAN;
            unscored[it->scene]++;
        }
    }
    for (int s = 0; s < c->n_scenes; s++)
        if (c->scenes[s].ref_path[0])
            compare_ref_measure(&c->scenes[s]);
        else
            c->scenes[s].ref_relmse = c->scenes[s].ref_radiance = c->scenes[s].ref_radiance_se = NAN;
    (void)compare_cost_read(c, dir); /* absent (an older folder): the images' own times, said so */
    int rc = verdict_from_compare(c, dir, out, e);
    for (int s = 0; rc == 0 && s < out->n_scenes && s < c->n_scenes; s++) {
        struct verdict_scene *vs = &out->scenes[s];
        if (missing[s] && vs->n_warnings < VERDICT_SAY_MAX)
            snprintf(
                vs->warnings[vs->n_warnings++], VERDICT_TEXT_MAX,
                "skipped: non-finite samples and what needs each variant's sampler (%d sidecar%s missing)",
                missing[s], missing[s] == 1 ? "" : "s");
        if (unscored[s] && vs->n_warnings < VERDICT_SAY_MAX)
            snprintf(vs->warnings[vs->n_warnings++], VERDICT_TEXT_MAX,
                     "left out: %d image%s whose relmse in summary.csv is not an error (not a number >= 0)",
                     unscored[s], unscored[s] == 1 ? "" : "s");
    }
    free(missing); /* and unscored */
    compare_free(c);
    return rc;
}

int verdict_load_dir(const char *dir, struct verdict_study **out, int *n, char *job, size_t job_n,
                     struct err *e)
{
    char path[JOB_PATH_MAX + 16];
    uint8_t *text = NULL;
    size_t len;
    struct csv t = {0};
    int col[N_COLS], rc = -1;
    *out = NULL, *n = 0;
    size_t end = strlen(dir), start;
    while (end > 1 && dir[end - 1] == '/') /* "out/study/": its last name */
        end--;
    for (start = end; start > 0 && dir[start - 1] != '/'; start--)
        ;
    snprintf(job, job_n, "%.*s", (int)(end - start), dir + start);
    snprintf(path, sizeof path, "%s/summary.csv", dir);
    if (fileio_read_all(path, CSV_MAX_BYTES, &text, &len, e) < 0 ||
        csv_parse(&t, (char *)text, len, path, e) < 0)
        goto done;
    for (int k = 0; k < N_COLS; k++) {
        col[k] = -1;
        for (int f = 0; t.n_rows && f < t.n_fields; f++)
            if (!strcmp(t.rows[0][f], col_names[k]))
                col[k] = f;
        if (col[k] < 0 && k != C_STUDY && k != C_LOWFREQ) {
            err_set(e, path, 1, 0, "no column %s", col_names[k]);
            goto done;
        }
    }
    char(*studies)[COMPARE_LABEL_MAX] = calloc((size_t)t.n_rows + 1, sizeof *studies);
    int n_studies = 0;
    if (!studies) {
        err_set(e, path, 0, 0, "out of memory");
        goto done;
    }
    if (col[C_STUDY] < 0)
        intern(studies, &n_studies, job);
    for (int r = 1; col[C_STUDY] >= 0 && r < t.n_rows && n_studies <= 64; r++)
        intern(studies, &n_studies, t.rows[r][col[C_STUDY]]);
    if (n_studies > 64) {
        free(studies);
        err_set(e, path, 0, 0, "more than 64 studies");
        goto done;
    }
    *out = calloc((size_t)(n_studies ? n_studies : 1), sizeof **out);
    rc = *out ? 0 : err_set(e, path, 0, 0, "out of memory");
    for (int i = 0; rc == 0 && i < n_studies; i++) {
        char sdir[JOB_PATH_MAX * 2];
        if (col[C_STUDY] >= 0)
            snprintf(sdir, sizeof sdir, "%s/%s", dir, studies[i]);
        else
            snprintf(sdir, sizeof sdir, "%s", dir);
        rc = judge(&t, col, studies[i], sdir, &(*out)[i], e);
        *n += rc == 0;
    }
    free(studies);
done:
    free(t.rows);
    free(text);
    return rc;
}
