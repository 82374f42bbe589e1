/* verdict_load: a compare output folder's summary.csv, sidecars and images back into a struct
   compare, judged again. */
#include "verdict_load.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fileio.h"
#include "compare.h"
#include "compare_cost.h"
#include "compare_ref.h"
#include "verdict_csv.h"
#include "verdict_points.h"
#include "verdict_sidecars.h"
#include "study/judge/verdict_from.h"

#define CSV_MAX_BYTES (64u << 20)
/* The figures a render can give: samples per pixel up to a job's most camera samples on one pixel
   (job_limits.h's LIMITS_MAX_JOB_SAMPLES), seconds up to about 30 years. */
#define SPP_MAX 1e11
#define SECONDS_MAX 1e9

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

/* summary.csv read: its rows, the column of each name (-1: absent), each row's study index. */
struct table {
    struct verdict_csv t;
    int col[N_COLS];
    int *study; /* per row (row 0, the header: -1) */
    const char *path;
};

/* Row r's field k, a name checked: 1 to max bytes (a compare job's limit, so a name is never cut
   and two names stay two) and, for a file's or a folder's name, no path. 0 or -1 with e at r. */
static int name_ok(const struct table *T, int r, int k, size_t max, struct err *e)
{
    const char *s = T->t.rows[r][T->col[k]];
    size_t n = strlen(s);
    if (n == 0 || n > max)
        return err_set(e, T->path, r + 1, 0, "%s: %zu bytes, not 1 to %zu", col_names[k], n, max);
    if ((k == C_IMAGE || k == C_STUDY) && (strchr(s, '/') || !strcmp(s, ".") || !strcmp(s, "..")))
        return err_set(e, T->path, r + 1, 0, "%s: a file name, not a path", col_names[k]);
    return 0;
}

/* Row r's threshold, light_threshold and seed checked as numbers (the seed a whole one): 0 or -1. */
static int numbers_ok(const struct table *T, int r, double *th, double *lt, uint64_t *seed, struct err *e)
{
    char *const *f = T->t.rows[r];
    const char *s = f[T->col[C_SEED]];
    if (verdict_csv_figure(f[T->col[C_THRESHOLD]], 0, 1e6, th) < 0 ||
        verdict_csv_figure(f[T->col[C_LT]], 0, 1e6, lt) < 0)
        return err_set(e, T->path, r + 1, 0, "threshold and light_threshold: numbers in [0, 1e6]");
    char *end;
    errno = 0;
    *seed = strtoull(s, &end, 10);
    if (!(*s >= '0' && *s <= '9') || *end || errno == ERANGE)
        return err_set(e, T->path, r + 1, 0, "seed: not a whole number below 2^64");
    return 0;
}

/* The first n names of set into labels (each checked to fit by name_ok). */
static void copy_names(const struct verdict_names *set, char (*labels)[COMPARE_LABEL_MAX])
{
    for (int i = 0; i < set->n; i++)
        snprintf(labels[i], COMPARE_LABEL_MAX, "%.*s", (int)set->len[i], set->s[i]);
}

/* A study's rows in the table, interned: per row its index and scene, variant and seed indices. */
struct interned {
    struct verdict_names scenes, variants, seeds, keys;
    int *rows; /* 4 per row: row, scene, variant, seed */
    int *point, *key_point, *top;
    int m;
};

static void interned_free(struct interned *I)
{
    verdict_names_free(&I->scenes), verdict_names_free(&I->variants);
    verdict_names_free(&I->seeds), verdict_names_free(&I->keys);
    free(I->rows), free(I->point), free(I->key_point), free(I->top);
}

/* Intern study si's rows (names whole, in linear time) and number its points: each (scene,
   variant)'s keys in order, a key seen before keeping its point. 0 or -1 with e filled. */
static int intern_rows(const struct table *T, int si, struct compare *c, struct interned *I, struct err *e)
{
    const struct verdict_csv *t = &T->t;
    I->m = 0;
    for (int r = 1; r < t->n_rows; r++)
        I->m += T->study[r] == si;
    if (I->m == 0)
        return err_set(e, T->path, 0, 0, "no rows for study %s", c->name);
    if (I->m > COMPARE_MAX_ITEMS)
        return err_set(e, T->path, 0, 0, "study %s has %d rows, more than a compare job's %d", c->name, I->m,
                       COMPARE_MAX_ITEMS);
    size_t m = (size_t)I->m, sv, n_items;
    I->rows = calloc(4 * m, sizeof *I->rows), I->point = calloc(m, sizeof *I->point);
    I->key_point = calloc(m, sizeof *I->key_point);
    c->points = calloc(m, sizeof *c->points);
    if (verdict_names_init(&I->scenes, I->m) < 0 || verdict_names_init(&I->variants, I->m) < 0 ||
        verdict_names_init(&I->seeds, I->m) < 0 || verdict_names_init(&I->keys, I->m) < 0 || !I->rows ||
        !I->point || !I->key_point || !c->points)
        return err_set(e, T->path, 0, 0, "out of memory");
    for (int r = 1, i = 0; r < t->n_rows; r++) {
        char *const *f = t->rows[r];
        double th, lt;
        uint64_t seed;
        if (T->study[r] != si)
            continue;
        if (name_ok(T, r, C_SCENE, COMPARE_LABEL_MAX - 1, e) < 0 ||
            name_ok(T, r, C_VARIANT, COMPARE_LABEL_MAX - 1, e) < 0 ||
            name_ok(T, r, C_IMAGE, JOB_NAME_MAX - 1, e) < 0 || numbers_ok(T, r, &th, &lt, &seed, e) < 0)
            return -1;
        int *x = &I->rows[4 * i++];
        x[0] = r;
        x[1] = verdict_names_intern(&I->scenes, f[T->col[C_SCENE]], strlen(f[T->col[C_SCENE]]));
        x[2] = verdict_names_intern(&I->variants, f[T->col[C_VARIANT]], strlen(f[T->col[C_VARIANT]]));
        x[3] = verdict_names_intern(&I->seeds, f[T->col[C_SEED]], strlen(f[T->col[C_SEED]]));
    }
    c->n_scenes = I->scenes.n, c->n_variants = I->variants.n, c->n_seeds = I->seeds.n;
    if (verdict_csv_product((size_t)c->n_scenes, (size_t)c->n_variants, COMPARE_MAX_ITEMS, &sv) < 0)
        goto too_many;
    I->top = malloc(sv * sizeof *I->top);
    if (!I->top)
        return err_set(e, T->path, 0, 0, "out of memory");
    for (size_t k = 0; k < sv; k++)
        I->top[k] = -1; /* the highest point of each (scene, variant) so far */
    for (int i = 0; i < I->m; i++) {
        const int *x = &I->rows[4 * i];
        char *const *f = t->rows[x[0]];
        const char *image = f[T->col[C_IMAGE]];
        int before = I->keys.n, k = verdict_names_intern(&I->keys, image, verdict_point_key_len(image));
        int *top = &I->top[x[1] * c->n_variants + x[2]];
        int p = k < before ? I->key_point[k] : *top + 1;
        I->key_point[k] = p;
        *top = p > *top ? p : *top;
        I->point[i] = p;
        if (p == c->n_points) { /* a new point: labelled by its first row's thresholds, or spp */
            c->n_points++;
            long spp = verdict_point_spp(image, verdict_point_key_len(image));
            if (spp > 0)
                snprintf(c->points[p], COMPARE_LABEL_MAX, "spp %ld, light_threshold %g", spp,
                         atof(f[T->col[C_LT]]));
            else
                snprintf(c->points[p], COMPARE_LABEL_MAX, "threshold %g, light_threshold %g",
                         atof(f[T->col[C_THRESHOLD]]), atof(f[T->col[C_LT]]));
        }
    }
    if (verdict_csv_product(sv, (size_t)c->n_points, COMPARE_MAX_ITEMS, &n_items) < 0 ||
        verdict_csv_product(n_items, (size_t)c->n_seeds, COMPARE_MAX_ITEMS, &n_items) < 0)
        goto too_many;
    c->n_items = (int)n_items;
    return 0;
too_many:
    return err_set(e, T->path, 0, 0,
                   "study %s: too many combinations (%d scenes x %d variants x %d points x %d seeds: more "
                   "than a compare job's %d images)",
                   c->name, c->n_scenes, c->n_variants, c->n_points, c->n_seeds, COMPARE_MAX_ITEMS);
}

/* Row f's figures into it; -1 (it left out) when spp, seconds or share are no figure in range. */
static int read_figures(const struct table *T, char *const *f, struct study_result *it)
{
    const int *col = T->col;
    double lowfreq;
    it->has_error = f[col[C_RELMSE]][0] != 0;
    if (!it->has_error || verdict_csv_figure(f[col[C_RELMSE]], 0, HUGE_VAL, &it->error.relmse) < 0)
        it->error.relmse = NAN; /* no error: judge() leaves it out and says so */
    it->error_lowfreq =
        col[C_LOWFREQ] >= 0 && verdict_csv_figure(f[col[C_LOWFREQ]], 0, HUGE_VAL, &lowfreq) == 0 ? lowfreq
                                                                                                 : NAN;
    if (verdict_csv_figure(f[col[C_SPP]], 0, SPP_MAX, &it->spp_mean) < 0 ||
        verdict_csv_figure(f[col[C_WALL]], 0, SECONDS_MAX, &it->wall_s) < 0 ||
        verdict_csv_figure(f[col[C_CPU]], 0, SECONDS_MAX, &it->cpu_s) < 0 ||
        verdict_csv_figure(f[col[C_SHARE]], 0, 1, &it->sampler_share) < 0) {
        *it = (struct study_result){0};
        return -1;
    }
    return 0;
}

/* Study si's rows into a struct compare; said: per scene 3 counts (sidecars missing, relMSEs that
   are no error, images left out for figures that are none), malloc'd, the last filled here. */
static struct compare *build(const struct table *T, int si, const char *study, const char *dir, int **said,
                             struct err *e)
{
    struct compare *c = calloc(1, sizeof *c);
    struct interned I = {0};
    if (!c) {
        err_set(e, dir, 0, 0, "out of memory");
        return NULL;
    }
    snprintf(c->name, sizeof c->name, "%s", study);
    if (intern_rows(T, si, c, &I, e) < 0)
        goto fail;
    /* light_threshold named only when the points differ in it */
    const char *lt = c->n_points ? strstr(c->points[0], ", light_threshold") : NULL;
    int same = lt != NULL;
    for (int p = 1; same && p < c->n_points; p++)
        same = strstr(c->points[p], lt) != NULL;
    for (int p = 0; same && p < c->n_points; p++)
        *strstr(c->points[p], ", light_threshold") = 0;
    c->scenes = calloc((size_t)c->n_scenes, sizeof *c->scenes);
    c->variants = calloc((size_t)c->n_variants, sizeof *c->variants);
    c->seeds = calloc((size_t)c->n_seeds, sizeof *c->seeds);
    c->items = calloc((size_t)c->n_items, sizeof *c->items);
    if (study_results_init(&c->results, c->n_items) < 0)
        c->items = (free(c->items), NULL);
    *said = calloc(3 * (size_t)c->n_scenes, sizeof **said);
    if (!c->scenes || !c->variants || !c->seeds || !c->items || !*said) {
        err_set(e, dir, 0, 0, "out of memory");
        goto fail;
    }
    copy_names(&I.variants, c->variants);
    for (int s = 0; s < c->n_scenes; s++) {
        snprintf(c->scenes[s].name, sizeof c->scenes[s].name, "%.*s", (int)I.scenes.len[s], I.scenes.s[s]);
        c->scenes[s].ref_domain = IMG_DISPLAY8;
    }
    for (int k = 0; k < c->n_seeds; k++)
        c->seeds[k] = strtoull(I.seeds.s[k], NULL, 10); /* checked whole by numbers_ok */
    for (int i = 0; i < I.m; i++) {
        char *const *f = T->t.rows[I.rows[4 * i]];
        int s = I.rows[4 * i + 1], v = I.rows[4 * i + 2], k = I.rows[4 * i + 3];
        struct compare_item *it = &c->items[compare_index(c, s, v, I.point[i], k)];
        struct study_result *r = &c->results.rows[compare_index(c, s, v, I.point[i], k)];
        *it = (struct compare_item){.scene = s, .variant = v, .point = I.point[i], .seed = k};
        *r = (struct study_result){.done = 1};
        if (read_figures(T, f, r) < 0) {
            (*said)[2 * c->n_scenes + s]++;
            continue;
        }
        snprintf(it->job.output, sizeof it->job.output, "%s", f[T->col[C_IMAGE]]);
        if (r->has_error) {
            c->scenes[s].ref_kind = COMPARE_REF_SETTINGS;
            if (!strcmp(f[T->col[C_DOMAIN]], "linear"))
                c->scenes[s].ref_domain = IMG_LINEAR;
        }
    }
    interned_free(&I);
    return c;
fail:
    interned_free(&I);
    free(*said);
    *said = NULL;
    compare_free(c);
    return NULL;
}

/* Judge study si in dir; a warning per scene names what was skipped or left out. */
static int judge(const struct table *T, int si, const char *study, const char *dir, struct verdict_study *out,
                 struct err *e)
{
    int *missing = NULL;
    struct compare *c = build(T, si, study, dir, &missing, e);
    if (!c)
        return -1;
    int *unscored = missing + c->n_scenes, *unfigured = missing + 2 * c->n_scenes;
    verdict_sidecars_read(c, dir, missing);
    for (int i = 0; i < c->n_items; i++) { /* a relmse that is no error ("nan", "-1"): left out, said */
        struct study_result *r = &c->results.rows[i];
        if (r->done && r->has_error && !(isfinite(r->error.relmse) && r->error.relmse >= 0)) {
            r->error.relmse = NAN;
            unscored[c->items[i].scene]++;
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
        if (unfigured[s] && vs->n_warnings < VERDICT_SAY_MAX)
            snprintf(vs->warnings[vs->n_warnings++], VERDICT_TEXT_MAX,
                     "left out: %d image%s whose samples_per_pixel_mean, wall_s, cpu_s or sampler_share in "
                     "summary.csv is not a figure (spp in [0, %g], seconds in [0, %g], share in [0, 1])",
                     unfigured[s], unfigured[s] == 1 ? "" : "s", SPP_MAX, SECONDS_MAX);
    }
    free(missing); /* and unscored, unfigured */
    compare_free(c);
    return rc;
}

/* The columns by name into T->col, and each row's study (a suite's, else the folder's job) into
   T->study, interned whole into studies (at most 64). 0 or -1 with e filled. */
static int index_table(struct table *T, const char *job, struct verdict_names *studies, struct err *e)
{
    const struct verdict_csv *t = &T->t;
    for (int k = 0; k < N_COLS; k++) {
        T->col[k] = -1;
        for (int f = 0; t->n_rows && f < t->n_fields; f++)
            if (!strcmp(t->rows[0][f], col_names[k]))
                T->col[k] = f;
        if (T->col[k] < 0 && k != C_STUDY && k != C_LOWFREQ)
            return err_set(e, T->path, 1, 0, "no column %s", col_names[k]);
    }
    T->study = calloc((size_t)t->n_rows, sizeof *T->study);
    if (!T->study || verdict_names_init(studies, 64) < 0)
        return err_set(e, T->path, 0, 0, "out of memory");
    T->study[0] = -1;
    for (int r = 1; r < t->n_rows; r++) {
        const char *s = T->col[C_STUDY] >= 0 ? t->rows[r][T->col[C_STUDY]] : job;
        if (T->col[C_STUDY] >= 0 && name_ok(T, r, C_STUDY, VERDICT_LABEL_MAX - 1, e) < 0)
            return -1;
        T->study[r] = verdict_names_intern(studies, s, strlen(s));
        if (T->study[r] < 0)
            return err_set(e, T->path, r + 1, 0, "more than 64 studies");
    }
    if (studies->n == 0 && verdict_names_intern(studies, job, strlen(job)) < 0)
        return err_set(e, T->path, 0, 0, "out of memory");
    return 0;
}

int verdict_load_dir(const char *dir, struct verdict_study **out, int *n, char *job, size_t job_n,
                     struct err *e)
{
    char path[JOB_PATH_MAX + 16];
    uint8_t *text = NULL;
    size_t len;
    struct table T = {.path = path};
    struct verdict_names studies = {0};
    int rc = -1;
    *out = NULL, *n = 0;
    size_t end = strlen(dir), start;
    while (end > 1 && dir[end - 1] == '/') /* "out/study/": its last name */
        end--;
    for (start = end; start > 0 && dir[start - 1] != '/'; start--)
        ;
    snprintf(job, job_n, "%.*s", (int)(end - start), dir + start);
    snprintf(path, sizeof path, "%s/summary.csv", dir);
    if (fileio_read_all(path, CSV_MAX_BYTES, &text, &len, e) < 0 ||
        verdict_csv_parse(&T.t, (char *)text, len, path, e) < 0 || index_table(&T, job, &studies, e) < 0)
        goto done;
    *out = calloc((size_t)studies.n, sizeof **out);
    rc = *out ? 0 : err_set(e, path, 0, 0, "out of memory");
    for (int i = 0; rc == 0 && i < studies.n; i++) {
        char sdir[JOB_PATH_MAX * 2], name[VERDICT_LABEL_MAX];
        snprintf(name, sizeof name, "%.*s", (int)studies.len[i], studies.s[i]);
        if (T.col[C_STUDY] >= 0)
            snprintf(sdir, sizeof sdir, "%s/%s", dir, name);
        else
            snprintf(sdir, sizeof sdir, "%s", dir);
        rc = judge(&T, i, name, sdir, &(*out)[i], e);
        *n += rc == 0;
    }
done:
    if (rc < 0) { /* nothing half judged is handed back */
        for (int i = 0; i < *n; i++)
            verdict_study_free(&(*out)[i]);
        free(*out);
        *out = NULL, *n = 0;
    }
    verdict_names_free(&studies);
    free(T.study);
    verdict_csv_free(&T.t);
    free(text);
    return rc;
}
