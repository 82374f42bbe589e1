/* test_study_table: summary.csv read back as a study's plan and results: points told by the
   settings columns (whatever the images are named), a seed repeated at the same settings opening the
   next point (a setting without a column), labels naming the settings the points differ in, an spp
   sweep told from each variant's sampler and threshold, and a bad row refused at its line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "compare_fixture.h"
#include "study/load/study_table.h"

#define HEAD                                                                                                 \
    "scene,variant,threshold,light_threshold,seed,samples_per_pixel_mean,wall_s,cpu_s,sampler_share,relmse," \
    "domain,image\n"

static struct compare_fixture fx;

/* The study of the table text, read from a file; NULL (checked) on failure. */
static struct compare *study(const char *text, struct study_table *t, int **unfigured)
{
    struct err e;
    *unfigured = NULL;
    if (study_table_read(t, compare_fixture_file(&fx, "summary.csv", text), "job", &e) < 0) {
        CHECK(!"study_table_read");
        return NULL;
    }
    struct compare *c = study_table_study(t, 0, unfigured, &e);
    CHECK(c != NULL);
    return c;
}

static void done(struct compare *c, struct study_table *t, int *unfigured)
{
    free(unfigured);
    compare_free(c);
    study_table_free(t);
}

/* Points from the settings columns: the images' names say nothing; light_threshold is named, as the
   points differ in it; a figure out of range leaves its image out, counted. */
static void test_points(void)
{
    struct study_table t;
    int *unfigured;
    struct compare *c = study(HEAD "a,x,20,10,1,16,1,1,0.1,0.5,linear,q.png\n"
                                   "a,x,20,10,2,16,1,1,0.1,0.4,linear,w.png\n"
                                   "a,x,10,5,1,64,1,1,0.1,0.2,linear,e.png\n"
                                   "a,x,10,5,2,64,1,1,0.1,0.1,linear,r.png\n"
                                   "a,y,20,5,1,16,1,1,0.1,0.3,linear,t.png\n"
                                   "a,y,20,5,2,16,1,1,0.1,0.3,linear,y.png\n"
                                   "a,y,10,5,1,64,1,1,0.1,0.1,linear,u.png\n"
                                   "a,y,10,5,2,bad,1,1,0.1,0.1,linear,i.png\n",
                              &t, &unfigured);
    if (c) {
        CHECK(c->n_scenes == 1 && c->n_variants == 2 && c->n_points == 2 && c->n_seeds == 2);
        CHECK(strcmp(c->points[0], "threshold 20, light_threshold 10") == 0);
        CHECK(strcmp(c->points[1], "threshold 10, light_threshold 5") == 0);
        const struct compare_item *it = &c->items[compare_index(c, 0, 1, 1, 0)];
        CHECK(strcmp(it->job.output, "u.png") == 0 && it->job.spec.pixel.threshold == 10 &&
              it->job.spec.light.threshold == 5);
        CHECK(c->results.rows[compare_index(c, 0, 0, 1, 1)].error.relmse == 0.1);
        CHECK(!c->results.rows[compare_index(c, 0, 1, 1, 1)].done && unfigured[0] == 1);
        CHECK(c->scenes[0].ref_kind == COMPARE_REF_SETTINGS && c->scenes[0].ref_domain == IMG_LINEAR);
    }
    done(c, &t, unfigured);
}

/* A sweep over a setting summary.csv has no column for (poisson_pool): the seeds repeat at the same
   settings, each repetition the next point; light_threshold, the same throughout, is not named. */
static void test_repeated_seeds(void)
{
    struct study_table t;
    int *unfigured;
    struct compare *c = study(HEAD "a,x,5,10,1,16,1,1,0.1,0.5,,p0-s1.png\n"
                                   "a,x,5,10,2,16,1,1,0.1,0.4,,p0-s2.png\n"
                                   "a,x,5,10,1,16,1,1,0.1,0.3,,p16-s1.png\n"
                                   "a,x,5,10,2,16,1,1,0.1,0.2,,p16-s2.png\n",
                              &t, &unfigured);
    if (c) {
        CHECK(c->n_points == 2 && c->n_seeds == 2 && c->n_items == 4);
        CHECK(strcmp(c->points[1], "threshold 5") == 0);
        CHECK(strcmp(c->items[compare_index(c, 0, 0, 1, 0)].job.output, "p16-s1.png") == 0);
        CHECK(c->results.rows[compare_index(c, 0, 0, 1, 1)].error.relmse == 0.2);
    }
    done(c, &t, unfigured);
}

/* An spp sweep: the variants' thresholds differ at each point, their samplers' counts agree. */
static void test_spp(void)
{
    struct study_table t;
    int *unfigured;
    struct compare *c = study(HEAD "a,jit,50,10,1,4,1,1,0.1,0.5,,a.png\n"
                                   "a,jit,25,10,1,16,1,1,0.1,0.4,,b.png\n"
                                   "a,poi,39.21,10,1,4,1,1,0.1,0.3,,c.png\n"
                                   "a,poi,19.61,10,1,16,1,1,0.1,0.2,,d.png\n",
                              &t, &unfigured);
    if (c) {
        for (int p = 0; p < 2; p++) {
            c->items[compare_index(c, 0, 0, p, 0)].job.spec.pixel.kind = SAMPLER_JITTER;
            c->items[compare_index(c, 0, 1, p, 0)].job.spec.pixel.kind = SAMPLER_POISSON;
        }
        CHECK(strcmp(c->points[1], "threshold 25") == 0);
        study_table_label_spp(c);
        CHECK(strcmp(c->points[0], "spp 4") == 0 && strcmp(c->points[1], "spp 16") == 0);
    }
    done(c, &t, unfigured);
}

/* A threshold that is no number, a column missing: refused at file:line. */
/* The render spec's other columns tell points apart too (a pool sweep at one threshold), label the
   points, and come back into each item's spec; a value that is none of its setting's is refused. */
static void test_spec_columns(void)
{
    struct study_table t;
    int *unfigured;
    const char *head = "scene,variant,threshold,light_threshold,seed,samples_per_pixel_mean,wall_s,cpu_s,"
                       "sampler_share,relmse,domain,sampler,poisson_pool,image\n";
    char text[1024];
    snprintf(text, sizeof text,
             "%sa,x,5,5,1,16,1,1,0.1,0.5,linear,poisson,0,q.png\n"
             "a,x,5,5,1,16,1,1,0.1,0.4,linear,poisson,64,w.png\n",
             head);
    struct compare *c = study(text, &t, &unfigured);
    if (c) {
        CHECK(c->n_points == 2 && c->n_seeds == 1);
        CHECK(strcmp(c->points[1], "threshold 5, poisson_pool 64") == 0);
        const struct compare_item *it = &c->items[compare_index(c, 0, 0, 1, 0)];
        CHECK(it->job.spec.poisson_pool == 64 && it->job.spec.pixel.kind == SAMPLER_POISSON);
    }
    done(c, &t, unfigured);
    snprintf(text, sizeof text, "%sa,x,5,5,1,16,1,1,0.1,0.5,linear,poissonx,0,q.png\n", head);
    struct err e;
    CHECK(study_table_read(&t, compare_fixture_file(&fx, "summary.csv", text), "job", &e) < 0 &&
          strstr(e.msg, "sampler") && e.line == 2);
}

static void test_bad(void)
{
    struct study_table t;
    struct err e;
    const char *path = compare_fixture_file(&fx, "summary.csv", HEAD "a,x,abc,10,1,16,1,1,0.1,0.5,,a.png\n");
    CHECK(study_table_read(&t, path, "job", &e) < 0 && e.line == 2 && strstr(e.msg, "threshold"));
    path =
        compare_fixture_file(&fx, "summary.csv",
                             "scene,variant,threshold,seed,samples_per_pixel_mean,wall_s,cpu_s,sampler_share,"
                             "relmse,domain,image\na,x,5,1,16,1,1,0.1,0.5,,a.png\n");
    CHECK(study_table_read(&t, path, "job", &e) < 0 && e.line == 1 &&
          strcmp(e.msg, "no column light_threshold") == 0);
}

int main(void)
{
    if (compare_fixture_open(&fx, "test_study_table") < 0)
        return 1;
    test_points();
    test_repeated_seeds();
    test_spp();
    test_spec_columns();
    test_bad();
    compare_fixture_close(&fx);
    return check_report("test_study_table");
}
