/* Tests for job loading: SPEC's defaults, and messages that depend only on the job file. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "job/job.h"
#include "job/jobfile.h"
#include "job_fixture.h"

static struct job_fixture fx;

/* Write "scene: <the checker scene>" and text as DIR/name and load it; 0 or -1 (with e). */
static int load(const char *name, const char *text, struct job *j, struct err *e)
{
    char path[128];
    struct jobfile jf;
    int rc = job_fixture_open(&fx, name, text, path, sizeof path, &jf, e);
    *j = jf.job;
    jobfile_close(&jf);
    unlink(path);
    return rc;
}

static void test_defaults(void)
{
    struct job j;
    struct err e;
    CHECK(load("cornell-box.v2.yaml", "sampler: jitter\n", &j, &e) == 0);
    CHECK(!strcmp(j.name, "cornell-box.v2"));         /* the file's stem */
    CHECK(j.spec.width == 300 && j.spec.height == 0); /* height 0: from the camera's aspect */
    CHECK(j.spec.pixel.kind == SAMPLER_JITTER && j.spec.light.kind == SAMPLER_JITTER);
    CHECK(j.spec.light.threshold == 5 && j.spec.max_depth == 50 && j.spec.seed == 1 && j.processes == 2);
    CHECK(j.format == IMG_PNG && !strcmp(j.output, "cornell-box.v2.png"));

    CHECK(load("p.yaml", "format: ppm\nlight_sampler: poisson\n", &j, &e) == 0);
    CHECK(j.spec.light.kind == SAMPLER_POISSON && j.format == IMG_PPM && !strcmp(j.output, "p.ppm"));
    CHECK(load("q.yaml", "output: Q.PPM\n", &j, &e) == 0);
    CHECK(j.format == IMG_PPM);
}

/* An out-of-range threshold's message does not depend on what the caller's struct err held:
   it read e->msg to decide on the quoted-number note even when nothing had written it. */
static void test_threshold_message(void)
{
    struct job j;
    struct err e;
    memset(&e, 0, sizeof e);
    snprintf(e.msg, sizeof e.msg, "stale%s", YQUOTED_NOTE);
    CHECK(load("t.yaml", "threshold: 500\n", &j, &e) < 0);
    CHECK(strstr(e.msg, "threshold: must be a number in (0, 100], got \"500\"") == e.msg);
    CHECK(strstr(e.msg, "quoted") == NULL);
    CHECK(e.line == 2 && e.col == 12); /* after the scene line */
    CHECK(load("t.yaml", "threshold: \"5\"\n", &j, &e) < 0);
    CHECK(strstr(e.msg, "quoted") != NULL);
}

int main(void)
{
    if (job_fixture_init(&fx, "test_job") < 0)
        return 1;
    test_defaults();
    test_threshold_message();
    rmdir(fx.dir);
    return check_report("test_job");
}
