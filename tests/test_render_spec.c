/* test_render_spec: the render spec's one table round trips: a job file's text -> job -> spec ->
   sidecar JSON -> spec, and spec -> summary.csv row -> spec, equal in every field, for chosen and
   for many random valid specs; and the cache key's text, spelled as earlier keys were. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/fileio.h"
#include "base/rng.h"
#include "check.h"
#include "job/sidecar.h"
#include "study/load/study_table.h"
#include "job_fixture.h"

static struct job_fixture fx;

/* Every field of a and b equal (roulette as rendered: a -1 reads back as what it resolves to). A
   field is listed here by hand, not through the table, so a row the writers drop shows. */
static int spec_equal(const struct render_spec *a, const struct render_spec *b)
{
    int eq = a->width == b->width && a->height == b->height && a->pixel.kind == b->pixel.kind &&
             a->pixel.threshold == b->pixel.threshold && a->light.kind == b->light.kind &&
             a->light.threshold == b->light.threshold && a->light_sampling == b->light_sampling &&
             a->integrator == b->integrator && a->dims_all == b->dims_all &&
             render_spec_roulette(a) == b->roulette && a->poisson_pool == b->poisson_pool &&
             a->poisson_domain == b->poisson_domain && a->max_depth == b->max_depth && a->seed == b->seed;
    if (!eq) {
        char ta[512], tb[512];
        render_spec_key_text(a, "", ta, sizeof ta);
        render_spec_key_text(b, "", tb, sizeof tb);
        fprintf(stderr, "  wrote %s\n  read  %s\n", ta, tb);
    }
    return eq;
}

/* s written into a sidecar (as the render of a job of that spec) and read back into out. 0 or -1. */
static int via_sidecar(const struct render_spec *s, struct render_spec *out)
{
    static struct procs_result res = {.processes = 1};
    struct job j;
    job_defaults(&j, "jobs/spec.yaml");
    j.spec = *s;
    snprintf(j.output, sizeof j.output, "spec.png");
    struct sidecar sc = {&j, s->width, s->height, &res, NULL, IMG_LINEAR, j.output, 0};
    char *text = sidecar_json(&sc), path[128];
    struct sidecar_info info;
    struct err e;
    snprintf(path, sizeof path, "%s/spec.json", fx.dir);
    int rc =
        text && fileio_write_atomic(path, text, strlen(text), &e) == 0 && sidecar_read(path, &info, &e) == 0
            ? 0
            : -1;
    free(text);
    *out = info.spec;
    return rc;
}

/* s as summary.csv writes it (compare.c's columns around render_spec_csv's), read back by the
   product's one reader of that file, study_table: the plan's item's spec, the seed from the row. */
static int via_csv(const struct render_spec *s, struct render_spec *out)
{
    struct sbuf b = {0};
    sbuf_printf(&b, "scene,variant,");
    render_spec_csv(NULL, 1, &b);
    sbuf_printf(&b, "samples_per_pixel_mean,wall_s,cpu_s,sampler_share,relmse,domain,");
    render_spec_csv(NULL, 0, &b);
    sbuf_printf(&b, "image\nchecker,v,");
    render_spec_csv(s, 1, &b);
    sbuf_printf(&b, "4.00,0.5,0.5,0.1,0.01,linear,");
    render_spec_csv(s, 0, &b);
    sbuf_printf(&b, "checker-v-s1.png\n");
    char *text = sbuf_take(&b);
    struct err e;
    struct study_table t;
    int *unfigured = NULL, rc = -1;
    char path[600];
    snprintf(path, sizeof path, "%s/summary.csv", fx.dir);
    if (text && fileio_write_atomic(path, text, strlen(text), &e) == 0 &&
        study_table_read(&t, path, "job", &e) == 0) {
        struct compare *c = study_table_study(&t, 0, &unfigured, &e);
        if (c && c->n_items == 1) {
            *out = c->items[0].job.spec;
            out->seed = c->seeds[0];
            rc = 0;
        }
        compare_free(c);
        study_table_free(&t);
    }
    free(unfigured);
    free(text);
    return rc;
}

/* s as a job file's keys (every row: key: text; under sampler_dims: all, which refuses them, no light
   sampler or threshold), opened as a job; its spec into out. */
static int via_job_file(const struct render_spec *s, struct render_spec *out)
{
    int n;
    const struct render_spec_row *rows = render_spec_rows(&n);
    char yaml[1024] = "", text[64], path[128];
    for (int i = 0; i < n; i++) {
        size_t used = strlen(yaml);
        if (s->dims_all && (!strcmp(rows[i].key, "light_sampler") || !strcmp(rows[i].key, "light_threshold")))
            continue;
        snprintf(yaml + used, sizeof yaml - used, "%s: %s\n", rows[i].key,
                 render_spec_text(s, &rows[i], text, sizeof text));
    }
    struct jobfile jf;
    struct err e;
    int rc = job_fixture_open(&fx, "spec.yaml", yaml, path, sizeof path, &jf, &e);
    if (rc < 0)
        fprintf(stderr, "  %s\n", e.msg);
    *out = jf.job.spec;
    jobfile_close(&jf);
    unlink(path);
    return rc;
}

static void test_chosen(void)
{
    struct render_spec s, back, again;
    struct jobfile jf;
    struct err e;
    char path[128];
    const char *yaml = "width: 64\nheight: 48\nsampler: poisson\nthreshold: 2.5\nlight_sampler: sobol\n"
                       "light_threshold: 0.1\nlight_sampling: false\nintegrator: nee\nrussian_roulette: off\n"
                       "poisson_pool: 16\npoisson_domain: square\nmax_depth: 7\nseed: 2147483647\n";
    CHECK(job_fixture_open(&fx, "chosen.yaml", yaml, path, sizeof path, &jf, &e) == 0);
    s = jf.job.spec;
    jobfile_close(&jf);
    CHECK(s.width == 64 && s.height == 48 && s.pixel.kind == SAMPLER_POISSON && s.pixel.threshold == 2.5);
    CHECK(s.light.kind == SAMPLER_SOBOL && s.light.threshold == 0.1 && !s.light_sampling);
    CHECK(s.integrator == INTEGRATOR_NEE && s.roulette == 0 && s.poisson_pool == 16);
    CHECK(s.poisson_domain == POISSON_SQUARE && s.max_depth == 7 && s.seed == 2147483647 && !s.dims_all);
    CHECK(via_sidecar(&s, &back) == 0 && spec_equal(&s, &back));
    CHECK(via_csv(&s, &again) == 0 && spec_equal(&s, &again));
    /* roulette not given: read back as the integrator's default (on with nee), as rendered */
    s.roulette = -1;
    CHECK(via_sidecar(&s, &back) == 0 && back.roulette == 1 && spec_equal(&s, &back));
    /* a reference half's seed, mixed to 64 bits, reads back whole */
    s.seed = rng_mix64(5) | (1ULL << 63);
    CHECK(via_sidecar(&s, &back) == 0 && back.seed == s.seed);
    CHECK(via_csv(&s, &back) == 0 && back.seed == s.seed);
}

/* A uniform double in (0, 1], all 53 bits used. */
static double unit(struct rng *r)
{
    uint64_t bits = ((uint64_t)rng_u32(r) << 21) ^ rng_u32(r);
    return (double)((bits & ((1ULL << 53) - 1)) + 1) / 9007199254740992.0;
}

static long in(struct rng *r, long lo, long hi)
{
    return lo + (long)(((uint64_t)rng_u32(r) << 32 | rng_u32(r)) % (uint64_t)(hi - lo + 1));
}

/* A random spec, every field across its row's range; with job_file, one a job file may hold (sets
   within the size limit; under sampler_dims: all, the light sampler the default: the pixel sampler's
   at 5). */
static void random_spec(struct rng *r, int job_file, struct render_spec *s)
{
    int n;
    const struct render_spec_row *rows = render_spec_rows(&n);
    for (int i = 0; i < n; i++) {
        const struct render_spec_row *row = &rows[i];
        if (row->type == RS_THRESHOLD)
            *render_spec_threshold(s, row) = 100 * unit(r);
        else if (row->type == RS_SAMPLER)
            render_spec_put(s, row, (uint64_t)in(r, SAMPLER_UNIFORM, SAMPLER_ZSOBOL));
        else if (row->type == RS_BOOL)
            render_spec_put(s, row, (uint64_t)in(r, 0, 1));
        else if (row->type == RS_CHOICE) {
            int k = 0;
            while (row->names()[k])
                k++;
            render_spec_put(s, row, (uint64_t)in(r, 0, k - 1));
        } else
            render_spec_put(s, row, (uint64_t)in(r, row->lo, row->hi));
    }
    if (!job_file)
        return;
    double small = sampler_smallest_threshold(s->pixel.kind);
    s->pixel.threshold = small + (100 - small) * unit(r);
    small = sampler_smallest_threshold(s->light.kind);
    s->light.threshold = small + (100 - small) * unit(r);
    if (s->dims_all)
        s->light = (struct sampler_spec){s->pixel.kind, 5};
}

static void test_random(void)
{
    struct rng r;
    rng_seed(&r, 37, 1);
    int sidecar_ok = 0, csv_ok = 0, job_ok = 0;
    const int rounds = 300;
    for (int i = 0; i < rounds; i++) {
        struct render_spec s, back;
        random_spec(&r, 0, &s);
        sidecar_ok += via_sidecar(&s, &back) == 0 && spec_equal(&s, &back);
        csv_ok += via_csv(&s, &back) == 0 && spec_equal(&s, &back);
        random_spec(&r, 1, &s);
        job_ok += via_job_file(&s, &back) == 0 && spec_equal(&s, &back) && via_sidecar(&back, &back) == 0 &&
                  spec_equal(&s, &back);
    }
    CHECK(sidecar_ok == rounds);
    CHECK(csv_ok == rounds);
    CHECK(job_ok == rounds);
}

/* The cache key's text: the settings that change pixels, in the order and spelling earlier keys
   used (a change would find no output current). */
static void test_key_text(void)
{
    struct render_spec s;
    render_spec_defaults(&s);
    s.width = 32;
    s.height = 24;
    char text[512], want[512];
    int n = render_spec_key_text(&s, " ref 0", text, sizeof text);
    snprintf(want, sizeof want, "32x24 random 5 random 5 depth 50 seed 1 pool 0 lights 1 ref 0 worker %s",
             WORKER_VERSION);
    CHECK(strcmp(text, want) == 0 && n == (int)strlen(want));
    /* poisson with next-event estimation, sampler_dims: all (roulette on by the integrator's row) */
    s.width = s.height = 8;
    s.pixel = (struct sampler_spec){SAMPLER_POISSON, 2.5};
    s.integrator = INTEGRATOR_NEE;
    s.dims_all = 1;
    s.poisson_domain = POISSON_SQUARE;
    render_spec_key_text(&s, "", text, sizeof text);
    snprintf(want, sizeof want,
             "8x8 poisson 2.5 random 5 depth 50 seed 1 pool 0 lights 1 worker %s nee dims all poisson square "
             "padded uniformly roulette",
             WORKER_VERSION);
    CHECK(strcmp(text, want) == 0);
    /* the light sampler alone pooling still names the domain; roulette off when said */
    s.pixel.kind = SAMPLER_SOBOL;
    s.light.kind = SAMPLER_POISSON;
    s.dims_all = 0;
    s.roulette = 0;
    s.poisson_domain = POISSON_TORUS;
    render_spec_key_text(&s, "", text, sizeof text);
    snprintf(want, sizeof want,
             "8x8 sobol 2.5 poisson 5 depth 50 seed 1 pool 0 lights 1 worker %s nee poisson torus",
             WORKER_VERSION);
    CHECK(strcmp(text, want) == 0);
    /* cut to the buffer, the length says so */
    CHECK(render_spec_key_text(&s, "", text, 6) == 5 && strcmp(text, "8x8 s") == 0);
}

/* The table itself: every key found, every key a job file may hold fits struct job_pos, ranges
   checked in one place. */
static void test_table(void)
{
    int n;
    const struct render_spec_row *rows = render_spec_rows(&n);
    for (int i = 0; i < n; i++)
        CHECK(render_spec_find(rows[i].key) == &rows[i]);
    CHECK(render_spec_find("processes") == NULL);
    const char *keys[JOB_KEYS_MAX + 8];
    CHECK(job_key_list(keys, JOB_KEYS_MAX + 8) <= JOB_KEYS_MAX);
    const struct render_spec_row *t = render_spec_find("threshold"), *w = render_spec_find("width");
    CHECK(render_spec_in_range(t, 100) && !render_spec_in_range(t, 0) && !render_spec_in_range(t, 100.5));
    CHECK(render_spec_in_range(w, 1) && !render_spec_in_range(w, 0));
    struct render_spec s;
    render_spec_defaults(&s);
    CHECK(render_spec_set_text(&s, t, "0") < 0 && render_spec_set_text(&s, w, "-4") < 0);
    CHECK(render_spec_set_text(&s, render_spec_find("sampler"), "jiter") < 0);
    CHECK(render_spec_set_text(&s, render_spec_find("integrator"), "nee") == 0 &&
          s.integrator == INTEGRATOR_NEE);
}

int main(void)
{
    if (job_fixture_init(&fx, "test_render_spec") < 0) {
        fprintf(stderr, "test_render_spec: no temporary folder\n");
        return 1;
    }
    test_table();
    test_key_text();
    test_chosen();
    test_random();
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", fx.dir);
    CHECK(system(cmd) == 0);
    return check_report("test_render_spec");
}
