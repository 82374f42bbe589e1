/* Tests for job loading: SPEC's defaults, and messages that depend only on the job file. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "job/job.h"
#include "job/jobfile.h"

static char dir[64], scene[1024];

/* Write "scene: <the checker scene>" and text as DIR/name and load it; 0 or -1 (with e). */
static int load(const char *name, const char *text, struct job *j, struct err *e)
{
    char path[128];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f)
        return -2;
    fprintf(f, "scene: %s\n%s", scene, text);
    fclose(f);
    struct jobfile jf;
    int rc = jobfile_open(&jf, path, path, e);
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
    CHECK(!strcmp(j.name, "cornell-box.v2")); /* the file's stem */
    CHECK(j.width == 300 && j.height == 0);   /* height 0: from the camera's aspect */
    CHECK(j.sampler == SAMPLER_JITTER && j.light_sampler == SAMPLER_JITTER);
    CHECK(j.light_threshold == 5 && j.max_depth == 50 && j.seed == 1 && j.processes == 2);
    CHECK(j.format == IMG_PNG && !strcmp(j.output, "cornell-box.v2.png"));

    CHECK(load("p.yaml", "format: ppm\nlight_sampler: poisson\n", &j, &e) == 0);
    CHECK(j.light_sampler == SAMPLER_POISSON && j.format == IMG_PPM && !strcmp(j.output, "p.ppm"));
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
    snprintf(dir, sizeof dir, "/tmp/test_job_XXXXXX");
    if (!mkdtemp(dir) || !getcwd(scene, sizeof scene - 32))
        return 1;
    strcat(scene, "/scenes/checker.yaml"); /* the tests run from the repository's root */
    test_defaults();
    test_threshold_message();
    rmdir(dir);
    return check_report("test_job");
}
