/* test_compare_suite: loading suites (studies resolved beside the suite, every refusal at its
   file:line:col) and the suite's summary.csv and chart.svg from its studies; nothing is rendered. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "compare_fixture.h"
#include "study/load/compare_suite_load.h"
#include "study/run/compare_suite.h"
#include "study/present/compare_suite_out.h"

static struct compare_fixture fx;

/* A job file written into the scratch folder (compare_fixture_file); its path. */
static const char *file(const char *name, const char *text)
{
    return compare_fixture_file(&fx, name, text);
}

/* A tiny study named name with two variants, two points and two seeds (8 images). */
static void study(const char *file_name, const char *name)
{
    char text[512];
    snprintf(text, sizeof text,
             "name: %s\nscenes: [SCENE]\nwidth: 8\nseeds: [1, 2]\nsweep: { threshold: [50, 25] }\n"
             "variants:\n  - { sampler: jitter }\n  - { sampler: random }\n",
             name);
    file(file_name, text);
}

static void test_load(void)
{
    struct err e;
    study("studies/a.yaml", "alpha");
    study("studies/b.yaml", "beta");
    const char *path = file("suite.yaml", "name: top\nstudies: [studies/a.yaml, studies/b.yaml]\n");
    char a_path[512];
    snprintf(a_path, sizeof a_path, "%s/studies/a.yaml", fx.dir);
    struct compare_suite *s = compare_suite_load(path, &e);
    CHECK(s != NULL);
    if (!s) {
        fprintf(stderr, "%s:%d:%d: %s\n", e.file, e.line, e.col, e.msg);
        return;
    }
    CHECK(strcmp(s->name, "top") == 0 && s->n_studies == 2 && s->n_items == 16);
    CHECK(strcmp(s->studies[0]->name, "alpha") == 0 && strcmp(s->studies[1]->name, "beta") == 0);
    CHECK(strcmp(s->studies[0]->path, a_path) == 0); /* resolved beside the suite */
    /* the images are the suite's: their sidecars' job_file names the file that was run */
    CHECK(strcmp(s->studies[1]->items[7].job.path, path) == 0);
    compare_suite_free(s);
    /* no name: the file's stem */
    s = compare_suite_load(file("stem.yaml", "studies: [studies/a.yaml]\n"), &e);
    CHECK(s && strcmp(s->name, "stem") == 0);
    compare_suite_free(s);
}

/* Loading the suite file name (text written first) fails at line:col of file at_file with msg. */
static void refused(const char *name, const char *text, const char *at_file, int line, int col,
                    const char *msg)
{
    struct err e = {0};
    char want[512];
    struct compare_suite *s = compare_suite_load(file(name, text), &e);
    snprintf(want, sizeof want, "%s/%s", fx.dir, at_file);
    CHECK(s == NULL);
    compare_suite_free(s);
    int ok = strcmp(e.file, want) == 0 && e.line == line && e.col == col && strstr(e.msg, msg);
    if (!ok)
        fprintf(stderr, "%s: got %s:%d:%d: %s\n", name, e.file, e.line, e.col, e.msg);
    CHECK(ok);
}

static void test_errors(void)
{
    study("studies/a.yaml", "alpha");
    study("studies/twin.yaml", "alpha");
    file("studies/bad.yaml", "name: bad\nscenes: [SCENE]\nvariants:\n  - { sampler: jiter }\n");
    file("studies/nested.yaml", "name: n\nstudies: [a.yaml]\n");
    refused("e1.yaml", "studies: [studies/a.yaml]\nnmae: x\n", "e1.yaml", 2, 1, "did you mean \"name\"");
    refused("e2.yaml", "studies: [studies/a.yaml]\nseeds: [1]\n", "e2.yaml", 2, 1, "not allowed in a suite");
    refused("e3.yaml", "studies: [studies/a.yaml, studies/bad.yaml]\n", "studies/bad.yaml", 4, 16, "sampler");
    refused("e4.yaml", "studies: [studies/a.yaml, studies/twin.yaml]\n", "e4.yaml", 1, 27,
            "both named \"alpha\"");
    refused("e5.yaml", "studies: [studies/a.yaml, studies/a.yaml]\n", "e5.yaml", 1, 27, "listed twice");
    refused("e6.yaml", "studies: [studies/nested.yaml]\n", "studies/nested.yaml", 2, 1, "suites do not nest");
    refused("e7.yaml", "studies: [studies/gone.yaml]\n", "e7.yaml", 1, 11, "no study file at");
    refused("e8.yaml", "studies: [studies]\n", "e8.yaml", 1, 11, "is a directory, not a study file");
    refused("e9.yaml", "studies: []\n", "e9.yaml", 1, 10, "non-empty list");
    refused("e10.yaml", "studies: studies/a.yaml\n", "e10.yaml", 1, 10, "non-empty list");
    refused("e11.yaml", "name: x\nstudies:\n", "e11.yaml", 2, 9, "needs a value");
    refused("e13.yaml", "studies: [~]\n", "e13.yaml", 1, 11, "studies: an empty entry (null)");
    char many[2048] = "studies: [";
    for (int i = 0; i <= COMPARE_SUITE_MAX_STUDIES; i++)
        strcat(many, i ? ", studies/a.yaml" : "studies/a.yaml");
    strcat(many, "]\n");
    refused("e12.yaml", many, "e12.yaml", 1, 10, "at most 16");
    file("studies/csv.yaml", "name: summary.csv\nscenes: [SCENE]\nvariants:\n  - { sampler: jitter }\n");
    refused("e13.yaml", "studies: [studies/csv.yaml]\n", "e13.yaml", 1, 11, "as the suite's own");
}

static void test_outputs(void)
{
    struct err e;
    study("studies/a.yaml", "alpha");
    study("studies/b.yaml", "beta");
    struct compare_suite *s =
        compare_suite_load(file("out.yaml", "studies: [studies/a.yaml, studies/b.yaml]\n"), &e);
    CHECK(s != NULL);
    if (!s)
        return;
    /* the studies' own summary.csv, as compare_run writes them; a quoted field holds a line break */
    char path[512];
    snprintf(path, sizeof path, "%s/o", fx.dir);
    mkdir(path, 0755);
    snprintf(path, sizeof path, "%s/o/alpha", fx.dir);
    mkdir(path, 0755);
    snprintf(path, sizeof path, "%s/o/beta", fx.dir);
    mkdir(path, 0755);
    file("o/alpha/summary.csv", "scene,variant\n\"two\nlines\",jitter\nchecker,random\n");
    file("o/beta/summary.csv", "scene,variant\nchecker,jitter\n");
    snprintf(path, sizeof path, "%s/o", fx.dir);
    char *csv = compare_suite_csv(s, path, &e);
    CHECK(csv && strcmp(csv, "study,scene,variant\nalpha,\"two\nlines\",jitter\nalpha,checker,random\n"
                             "beta,checker,jitter\n") == 0);
    free(csv);
    /* a study's summary.csv missing: an error naming it */
    snprintf(path, sizeof path, "%s/nowhere", fx.dir);
    CHECK(compare_suite_csv(s, path, &e) == NULL && strstr(e.file, "nowhere/alpha/summary.csv"));
    /* the chart: one document, each study's chart nested below the one before */
    char *svg = compare_suite_chart_svg(s);
    int decls = 0, nested = 0, y[2] = {-1, -1};
    for (const char *p = svg ? strstr(svg, "<?xml") : NULL; p; p = strstr(p + 1, "<?xml"))
        decls++;
    for (const char *p = svg ? strstr(svg, "<svg x=\"0\" y=\"") : NULL; p;
         p = strstr(p + 1, "<svg x=\"0\" y=\""))
        if (nested < 2)
            sscanf(p, "<svg x=\"0\" y=\"%d\"", &y[nested++]);
        else
            nested++;
    CHECK(decls == 1 && nested == 2 && y[0] == 0 && y[1] > 0);
    CHECK(svg && strstr(svg, "alpha: relMSE") && strstr(svg, "beta: relMSE"));
    free(svg);
    compare_suite_free(s);
}

int main(void)
{
    if (compare_fixture_open(&fx, "test_compare_suite") < 0)
        return 1;
    char sub[300];
    snprintf(sub, sizeof sub, "%s/studies", fx.dir);
    mkdir(sub, 0755);
    test_load();
    test_errors();
    test_outputs();
    CHECK(compare_fixture_close(&fx) == 0);
    return check_report("test_compare_suite");
}
