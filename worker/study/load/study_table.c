/* study_table: summary.csv's rows read, checked and turned back into a study's plan and results. */
#include "study_table.h"

#include <errno.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fileio.h"
#include "render/render_spec.h"
#include "sample/sampler_kind.h"

/* The settings columns that place a row at its sweep point: every render_spec row (the table
   summary.csv writes its settings from) but seed, threshold and light_threshold first (every file
   has them: checked as numbers, and a label always names the first), the others in the table's
   order, each read as "" from a file written before it had their columns. */
static int point_settings(const struct render_spec_row **out)
{
    int n, k = 2;
    const struct render_spec_row *r = render_spec_rows(&n);
    out[0] = render_spec_find("threshold"), out[1] = render_spec_find("light_threshold");
    for (int i = 0; i < n && k < STUDY_TABLE_SETTINGS_MAX; i++)
        if (&r[i] != out[0] && &r[i] != out[1] && strcmp(r[i].key, "seed"))
            out[k++] = &r[i];
    return k;
}

struct study_table_row {
    int study; /* index into the table's studies */
    const char *scene, *variant, *image, *domain;
    const char *setting[STUDY_TABLE_SETTINGS_MAX]; /* the settings columns' fields ("" when absent) */
    double threshold, light_threshold;
    uint64_t seed;
    int figured; /* 0: spp, seconds or share no figure in range (res not done: left out, said) */
    struct study_result res;
};

/* The other columns read, by name (study, error_lowfreq optional: a suite's, a newer file's). */
enum {
    C_STUDY,
    C_SCENE,
    C_VARIANT,
    C_SEED,
    C_SPP,
    C_WALL,
    C_CPU,
    C_SHARE,
    C_RELMSE,
    C_DOMAIN,
    C_IMAGE,
    C_LOWFREQ,
    N_COLS
};
static const char *const col_names[N_COLS] = {
    "study",         "scene",  "variant", "seed",  "samples_per_pixel_mean", "wall_s", "cpu_s",
    "sampler_share", "relmse", "domain",  "image", "error_lowfreq"};

/* Field r's name in column k checked: 1 to max bytes (a compare job's limit, so a name is never cut
   and two names stay two) and, for a file's or a folder's name, no path. 0 or -1 with e at r. */
static int name_ok(const struct study_table *t, int r, int k, const char *s, size_t max, struct err *e)
{
    size_t n = strlen(s);
    if (n == 0 || n > max)
        return err_set(e, t->path, r + 1, 0, "%s: %zu bytes, not 1 to %zu", col_names[k], n, max);
    if ((k == C_IMAGE || k == C_STUDY) && (strchr(s, '/') || !strcmp(s, ".") || !strcmp(s, "..")))
        return err_set(e, t->path, r + 1, 0, "%s: a file name, not a path", col_names[k]);
    return 0;
}

/* Line r's threshold, light_threshold and seed checked as numbers (the seed a whole one). 0 or -1. */
static int numbers_ok(const struct study_table *t, int r, struct study_table_row *x, const char *seed,
                      struct err *e)
{
    if (verdict_csv_figure(x->setting[0], 0, 1e6, &x->threshold) < 0 ||
        verdict_csv_figure(x->setting[1], 0, 1e6, &x->light_threshold) < 0)
        return err_set(e, t->path, r + 1, 0, "threshold and light_threshold: numbers in [0, 1e6]");
    char *end;
    errno = 0;
    x->seed = strtoull(seed, &end, 10);
    if (!(*seed >= '0' && *seed <= '9') || *end || errno == ERANGE)
        return err_set(e, t->path, r + 1, 0, "seed: not a whole number below 2^64");
    return 0;
}

/* The row's spec: the defaults, its threshold and light_threshold (numbers_ok's), and each other
   setting it has a field for read through its row. */
static int row_spec(const struct study_table *t, const struct study_table_row *x, struct render_spec *spec)
{
    render_spec_defaults(spec);
    spec->pixel.threshold = x->threshold, spec->light.threshold = x->light_threshold;
    for (int k = 2; k < t->n_settings; k++)
        if (x->setting[k][0] && render_spec_set_text(spec, t->settings[k], x->setting[k]) < 0)
            return k;
    return 0;
}

/* Line r's settings each a value of its setting (or absent). 0 or -1 with e at r. */
static int settings_ok(const struct study_table *t, int r, const struct study_table_row *x, struct err *e)
{
    struct render_spec spec;
    int k = row_spec(t, x, &spec);
    return k ? err_set(e, t->path, r + 1, 0, "%s: \"%s\" is no value of the setting", t->settings[k]->key,
                       x->setting[k])
             : 0;
}

/* A row's figures into x->res (done); x->figured 0 (res emptied) when spp, seconds or share are no
   figure in range. A relmse that is no figure is NAN (the judge leaves it out and says so). */
static void read_figures(char *const *f, const int *col, struct study_table_row *x)
{
    struct study_result *r = &x->res;
    double lowfreq;
    *r = (struct study_result){.done = 1, .has_error = f[col[C_RELMSE]][0] != 0};
    if (!r->has_error || verdict_csv_figure(f[col[C_RELMSE]], 0, HUGE_VAL, &r->error.relmse) < 0)
        r->error.relmse = NAN;
    r->error_lowfreq =
        col[C_LOWFREQ] >= 0 && verdict_csv_figure(f[col[C_LOWFREQ]], 0, HUGE_VAL, &lowfreq) == 0 ? lowfreq
                                                                                                 : NAN;
    x->figured = verdict_csv_figure(f[col[C_SPP]], 0, STUDY_RESULTS_SPP_MAX, &r->spp_mean) == 0 &&
                 verdict_csv_figure(f[col[C_WALL]], 0, STUDY_RESULTS_SECONDS_MAX, &r->wall_s) == 0 &&
                 verdict_csv_figure(f[col[C_CPU]], 0, STUDY_RESULTS_SECONDS_MAX, &r->cpu_s) == 0 &&
                 verdict_csv_figure(f[col[C_SHARE]], 0, 1, &r->sampler_share) == 0;
    if (!x->figured)
        *r = (struct study_result){0};
}

/* The column of name in the header, or -1. */
static int column(const struct verdict_csv *csv, const char *name)
{
    for (int f = 0; csv->n_rows && f < csv->n_fields; f++)
        if (!strcmp(csv->rows[0][f], name))
            return f;
    return -1;
}

/* Every row of the parsed file into t->rows, checked. 0 or -1 with e filled. */
static int read_rows(struct study_table *t, const char *job, struct err *e)
{
    const struct verdict_csv *csv = &t->csv;
    int col[N_COLS], set[STUDY_TABLE_SETTINGS_MAX];
    t->n_settings = point_settings(t->settings);
    for (int k = 0; k < N_COLS; k++)
        if ((col[k] = column(csv, col_names[k])) < 0 && k != C_STUDY && k != C_LOWFREQ)
            return err_set(e, t->path, 1, 0, "no column %s", col_names[k]);
    for (int k = 0; k < t->n_settings; k++) { /* every file has the first two; a newer one may be absent */
        set[k] = column(csv, t->settings[k]->key);
        if (k < 2 && set[k] < 0)
            return err_set(e, t->path, 1, 0, "no column %s", t->settings[k]->key);
    }
    t->has_study = col[C_STUDY] >= 0;
    t->n_rows = csv->n_rows > 0 ? csv->n_rows - 1 : 0;
    t->rows = calloc((size_t)t->n_rows + 1, sizeof *t->rows);
    if (!t->rows || verdict_names_init(&t->studies, 64) < 0)
        return err_set(e, t->path, 0, 0, "out of memory");
    for (int i = 0; i < t->n_rows; i++) {
        char *const *f = csv->rows[i + 1];
        struct study_table_row *x = &t->rows[i];
        x->scene = f[col[C_SCENE]], x->variant = f[col[C_VARIANT]], x->image = f[col[C_IMAGE]];
        x->domain = f[col[C_DOMAIN]];
        for (int k = 0; k < t->n_settings; k++)
            x->setting[k] = set[k] >= 0 ? f[set[k]] : "";
        const char *study = t->has_study ? f[col[C_STUDY]] : job;
        if ((t->has_study && name_ok(t, i + 1, C_STUDY, study, VERDICT_LABEL_MAX - 1, e) < 0) ||
            name_ok(t, i + 1, C_SCENE, x->scene, COMPARE_LABEL_MAX - 1, e) < 0 ||
            name_ok(t, i + 1, C_VARIANT, x->variant, COMPARE_LABEL_MAX - 1, e) < 0 ||
            name_ok(t, i + 1, C_IMAGE, x->image, JOB_NAME_MAX - 1, e) < 0 ||
            numbers_ok(t, i + 1, x, f[col[C_SEED]], e) < 0 || settings_ok(t, i + 1, x, e) < 0)
            return -1;
        if ((x->study = verdict_names_intern(&t->studies, study, strlen(study))) < 0)
            return err_set(e, t->path, i + 2, 0, "more than 64 studies");
        read_figures(f, col, x);
    }
    if (t->studies.n == 0 && verdict_names_intern(&t->studies, job, strlen(job)) < 0)
        return err_set(e, t->path, 0, 0, "out of memory");
    return 0;
}

int study_table_read(struct study_table *t, const char *path, const char *job, struct err *e)
{
    uint8_t *text = NULL;
    size_t len;
    *t = (struct study_table){.path = path};
    if (fileio_read_all(path, 64u << 20, &text, &len, e) < 0) /* 64 studies of 4096 rows, with room */
        return -1;
    t->text = (char *)text;
    if (verdict_csv_parse(&t->csv, t->text, len, path, e) < 0 || read_rows(t, job, e) < 0) {
        study_table_free(t);
        return -1;
    }
    return 0;
}

void study_table_free(struct study_table *t)
{
    verdict_csv_free(&t->csv);
    verdict_names_free(&t->studies);
    free(t->rows);
    free(t->text);
    *t = (struct study_table){0};
}

/* A study's rows interned: per row of it, its table row, its scene, variant and seed indices and
   two keys (ints): its scene, variant and settings with its seed, and with its occurrence. */
struct interned {
    struct verdict_names scenes, variants, seeds, values, seen, keys;
    int *row, *svk /* 4 per row: scene, variant, seed, point */, *with_seed, *with_occ, *occ, *key_point,
        *top, *first;
    int m, w; /* rows; ints per key: scene, variant, each setting, then the seed or occurrence */
};

static void interned_free(struct interned *I)
{
    verdict_names_free(&I->scenes), verdict_names_free(&I->variants), verdict_names_free(&I->seeds);
    verdict_names_free(&I->values), verdict_names_free(&I->seen), verdict_names_free(&I->keys);
    free(I->row), free(I->svk), free(I->with_seed), free(I->with_occ), free(I->occ);
    free(I->key_point), free(I->top), free(I->first);
}

static int intern(struct verdict_names *n, const char *s)
{
    return verdict_names_intern(n, s, strlen(s));
}

/* Study si's rows interned (names whole, in linear time), each with its point's key: its scene,
   variant and settings, and how many rows before it had those and its seed. 0 or -1 (no memory). */
static int intern_rows(const struct study_table *t, int si, struct interned *I)
{
    size_t m = (size_t)I->m, w = (size_t)(I->w = 3 + t->n_settings);
    I->row = calloc(m, sizeof *I->row), I->svk = calloc(4 * m, sizeof *I->svk);
    I->with_seed = calloc(m * w, sizeof *I->with_seed), I->with_occ = calloc(m * w, sizeof *I->with_occ);
    I->occ = calloc(m, sizeof *I->occ), I->key_point = calloc(m, sizeof *I->key_point);
    I->first = calloc(m, sizeof *I->first);
    if (verdict_names_init(&I->scenes, I->m) < 0 || verdict_names_init(&I->variants, I->m) < 0 ||
        verdict_names_init(&I->seeds, I->m) < 0 || verdict_names_init(&I->values, I->m * t->n_settings) < 0 ||
        verdict_names_init(&I->seen, I->m) < 0 || verdict_names_init(&I->keys, I->m) < 0 || !I->row ||
        !I->svk || !I->with_seed || !I->with_occ || !I->occ || !I->key_point || !I->first)
        return -1;
    for (int r = 0, i = 0; r < t->n_rows; r++) {
        const struct study_table_row *x = &t->rows[r];
        if (x->study != si)
            continue;
        int *a = &I->with_seed[(size_t)i * w], *b = &I->with_occ[(size_t)i * w];
        I->row[i] = r;
        a[0] = I->svk[4 * i] = intern(&I->scenes, x->scene);
        a[1] = I->svk[4 * i + 1] = intern(&I->variants, x->variant);
        for (int j = 0; j < t->n_settings; j++)
            a[2 + j] = intern(&I->values, x->setting[j]);
        a[w - 1] = I->svk[4 * i + 2] =
            verdict_names_intern(&I->seeds, (const char *)&x->seed, sizeof x->seed);
        memcpy(b, a, w * sizeof *a);
        b[w - 1] = I->occ[verdict_names_intern(&I->seen, (const char *)a, w * sizeof *a)]++;
        i++;
    }
    return 0;
}

/* Each (scene, variant)'s points numbered in order of their keys, a key seen before keeping its
   point; the first row of each point kept. 0, -1 (too many combinations) or -2 (no memory). */
static int number_points(struct compare *c, struct interned *I)
{
    size_t sv, n_items;
    c->n_scenes = I->scenes.n, c->n_variants = I->variants.n, c->n_seeds = I->seeds.n;
    if (verdict_csv_product((size_t)c->n_scenes, (size_t)c->n_variants, COMPARE_MAX_ITEMS, &sv) < 0)
        return -1;
    if (!(I->top = malloc(sv * sizeof *I->top)))
        return -2;
    for (size_t k = 0; k < sv; k++)
        I->top[k] = -1; /* the highest point of each (scene, variant) so far */
    for (int i = 0; i < I->m; i++) {
        int *x = &I->svk[4 * i], before = I->keys.n;
        int k = verdict_names_intern(&I->keys, (const char *)&I->with_occ[(size_t)i * I->w],
                                     (size_t)I->w * sizeof *I->with_occ);
        int *top = &I->top[x[0] * c->n_variants + x[1]], p = k < before ? I->key_point[k] : *top + 1;
        I->key_point[k] = x[3] = p;
        *top = p > *top ? p : *top;
        if (p == c->n_points)
            I->first[c->n_points++] = i;
    }
    if (verdict_csv_product(sv, (size_t)c->n_points, COMPARE_MAX_ITEMS, &n_items) < 0 ||
        verdict_csv_product(n_items, (size_t)c->n_seeds, COMPARE_MAX_ITEMS, &n_items) < 0)
        return -1;
    c->n_items = (int)n_items;
    return 0;
}

/* Point p's setting j as its label shows it (a number as %g, else its text), into out. */
static const char *setting_text(const struct study_table *t, const struct interned *I, int p, int j,
                                char *out)
{
    double x;
    const char *field = t->rows[I->row[I->first[p]]].setting[j];
    if (verdict_csv_figure(field, -HUGE_VAL, HUGE_VAL, &x) == 0)
        snprintf(out, COMPARE_LABEL_MAX, "%g", x);
    else
        snprintf(out, COMPARE_LABEL_MAX, "%s", field);
    return out;
}

/* Each point labelled by its first row's settings: the first always, each other one when the points
   differ in it ("threshold 5, light_threshold 10"). */
static void label_points(const struct study_table *t, struct compare *c, const struct interned *I)
{
    char first[COMPARE_LABEL_MAX], v[COMPARE_LABEL_MAX];
    for (int p = 0; p < c->n_points; p++)
        c->points[p][0] = 0;
    for (int j = 0; j < t->n_settings; j++) {
        int differ = j == 0;
        setting_text(t, I, 0, j, first);
        for (int p = 1; p < c->n_points; p++)
            differ |= strcmp(setting_text(t, I, p, j, v), first) != 0;
        for (int p = 0; differ && p < c->n_points; p++) {
            size_t len = strlen(c->points[p]);
            snprintf(c->points[p] + len, COMPARE_LABEL_MAX - len, "%s%s %s", j ? ", " : "",
                     t->settings[j]->key, setting_text(t, I, p, j, v));
        }
    }
}

/* The rows into c's items and results (the plan's arrays allocated); unfigured[s] counted. */
static void fill(const struct study_table *t, struct compare *c, const struct interned *I, int *unfigured)
{
    for (int s = 0; s < c->n_scenes; s++) {
        snprintf(c->scenes[s].name, sizeof c->scenes[s].name, "%.*s", (int)I->scenes.len[s], I->scenes.s[s]);
        c->scenes[s].ref_domain = IMG_DISPLAY8;
    }
    for (int v = 0; v < c->n_variants; v++)
        snprintf(c->variants[v], COMPARE_LABEL_MAX, "%.*s", (int)I->variants.len[v], I->variants.s[v]);
    for (int k = 0; k < c->n_seeds; k++)
        memcpy(&c->seeds[k], I->seeds.s[k], sizeof c->seeds[k]);
    for (int i = 0; i < I->m; i++) {
        const struct study_table_row *x = &t->rows[I->row[i]];
        const int *a = &I->svk[4 * i];
        int n = compare_index(c, a[0], a[1], a[3], a[2]);
        struct compare_item *it = &c->items[n];
        *it = (struct compare_item){.scene = a[0], .variant = a[1], .point = a[3], .seed = a[2]};
        row_spec(t, x, &it->job.spec); /* checked by settings_ok */
        c->results.rows[n] = x->res;
        if (!x->figured) {
            unfigured[a[0]]++;
            continue;
        }
        snprintf(it->job.output, sizeof it->job.output, "%s", x->image);
        if (x->res.has_error) {
            c->scenes[a[0]].ref_kind = COMPARE_REF_SETTINGS;
            if (!strcmp(x->domain, "linear"))
                c->scenes[a[0]].ref_domain = IMG_LINEAR;
        }
    }
}

struct compare *study_table_study(const struct study_table *t, int si, int **unfigured, struct err *e)
{
    struct compare *c = calloc(1, sizeof *c);
    struct interned I = {0};
    *unfigured = NULL;
    if (!c) {
        err_set(e, t->path, 0, 0, "out of memory");
        return NULL;
    }
    snprintf(c->name, sizeof c->name, "%.*s", (int)t->studies.len[si], t->studies.s[si]);
    for (int r = 0; r < t->n_rows; r++)
        I.m += t->rows[r].study == si;
    if (I.m == 0 || I.m > COMPARE_MAX_ITEMS) {
        if (I.m == 0)
            err_set(e, t->path, 0, 0, "no rows for study %s", c->name);
        else
            err_set(e, t->path, 0, 0, "study %s has %d rows, more than a compare job's %d", c->name, I.m,
                    COMPARE_MAX_ITEMS);
        goto fail;
    }
    c->points = calloc((size_t)I.m, sizeof *c->points);
    if (!c->points || intern_rows(t, si, &I) < 0) {
        err_set(e, t->path, 0, 0, "out of memory");
        goto fail;
    }
    int numbered = number_points(c, &I);
    if (numbered < 0) {
        if (numbered == -2)
            err_set(e, t->path, 0, 0, "out of memory");
        else
            err_set(e, t->path, 0, 0,
                    "study %s: too many combinations (%d scenes x %d variants x %d points x %d seeds: more "
                    "than a compare job's %d images)",
                    c->name, c->n_scenes, c->n_variants, c->n_points, c->n_seeds, COMPARE_MAX_ITEMS);
        goto fail;
    }
    label_points(t, c, &I);
    c->scenes = calloc((size_t)c->n_scenes, sizeof *c->scenes);
    c->variants = calloc((size_t)c->n_variants, sizeof *c->variants);
    c->seeds = calloc((size_t)c->n_seeds, sizeof *c->seeds);
    c->items = calloc((size_t)c->n_items, sizeof *c->items);
    *unfigured = calloc((size_t)c->n_scenes, sizeof **unfigured);
    if (!c->scenes || !c->variants || !c->seeds || !c->items || !*unfigured ||
        study_results_init(&c->results, c->n_items, c->n_scenes) < 0) {
        err_set(e, t->path, 0, 0, "out of memory");
        goto fail;
    }
    fill(t, c, &I, *unfigured);
    interned_free(&I);
    return c;
fail:
    interned_free(&I);
    free(*unfigured);
    *unfigured = NULL;
    compare_free(c);
    return NULL;
}

void study_table_label_spp(struct compare *c)
{
    for (int p = 0; c->n_scenes && p < c->n_points; p++) {
        long spp = -1;
        int differ = 0;
        for (int v = 0; v < c->n_variants && spp != 0; v++) {
            const struct render_spec *j = &c->items[compare_index(c, 0, v, p, 0)].job.spec;
            const struct render_spec *j0 = &c->items[compare_index(c, 0, 0, p, 0)].job.spec;
            int valid = render_spec_in_range(render_spec_find("threshold"), j->pixel.threshold) &&
                        j->pixel.threshold >= sampler_smallest_threshold(j->pixel.kind);
            long n =
                valid ? lround(sampler_expected_spp(j->pixel.kind, j->pixel.threshold)) : 0; /* 0: a hole */
            differ |= j->pixel.threshold != j0->pixel.threshold;
            spp = spp < 0 || spp == n ? n : 0;
        }
        const char *rest = strchr(c->points[p], ',');
        if (differ && spp > 0) {
            char label[COMPARE_LABEL_MAX];
            snprintf(label, sizeof label, "spp %ld%s", spp, rest ? rest : "");
            memcpy(c->points[p], label, sizeof label);
        }
    }
}
