/* test_spread_plan: entry names read back, the predicted wall time of entries on a farm (list
   scheduling, images after every reference), and the plan file written and read back. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "base/fileio.h"
#include "farm/spread_plan.h"

static struct spread_entry entry(enum study_fan_kind kind, double cpu_s, int processes)
{
    struct spread_entry x = {.kind = kind, .est_cpu_s = cpu_s, .processes = processes, .parts = 1};
    snprintf(x.name, sizeof x.name, "%s",
             kind == STUDY_FAN_REFERENCE ? "a-ref-0-0-0.yaml" : "b-img-0-00000.yaml");
    return x;
}

static void names(void)
{
    struct spread_entry x;
    CHECK(spread_plan_parse("a-ref-1-2-1-p3-9.yaml", &x) == 0);
    CHECK(x.kind == STUDY_FAN_REFERENCE && x.k == 1 && x.index == 2 && x.half == 1 && x.part == 3 &&
          x.parts == 9);
    CHECK(spread_plan_parse("b-img-0-00012.yaml", &x) == 0);
    CHECK(x.kind == STUDY_FAN_IMAGE && x.k == 0 && x.index == 12 && x.part == 0 && x.parts == 1);
    CHECK(spread_plan_parse("b-img-0-00012-p4-5.yaml", &x) == 0 && x.part == 4 && x.parts == 5);
    /* what no plan makes */
    CHECK(spread_plan_parse("c-gather.yaml", &x) < 0);
    CHECK(spread_plan_parse("a-ref-0-0-2.yaml", &x) < 0);        /* a third half */
    CHECK(spread_plan_parse("b-img-0-00012-p5-5.yaml", &x) < 0); /* part out of its split */
    CHECK(spread_plan_parse("b-img-0-00012-p0-257.yaml", &x) < 0);
    CHECK(spread_plan_parse("b-img-0-00012.yaml.x", &x) < 0);
    CHECK(spread_plan_parse("b-img--1-00012.yaml", &x) < 0);
    CHECK(spread_plan_parse("0.yaml", &x) < 0);
}

static void makespan(void)
{
    struct spread_entry e[6];
    /* two references of 10 CPU s on 2 processes, then four images of 4 CPU s */
    e[0] = entry(STUDY_FAN_REFERENCE, 10, 2);
    e[1] = entry(STUDY_FAN_REFERENCE, 10, 2);
    for (int i = 2; i < 6; i++)
        e[i] = entry(STUDY_FAN_IMAGE, 4, 2);
    /* one worker of 2 cores: everything in a row, at 2 cores: 36 / 2 */
    CHECK_NEAR(spread_plan_makespan(e, 6, 1, 2), 18, 1e-9);
    /* two workers: the references side by side (5 s), then two images each (2 + 2 s) */
    CHECK_NEAR(spread_plan_makespan(e, 6, 2, 2), 9, 1e-9);
    /* eight workers: an image waits for the references, whatever the free workers */
    CHECK_NEAR(spread_plan_makespan(e, 6, 8, 2), 7, 1e-9);
    /* one core a worker: an entry's wall is its CPU */
    CHECK_NEAR(spread_plan_makespan(e, 6, 8, 1), 14, 1e-9);
    /* one process an entry: the second core idle */
    e[0].processes = e[1].processes = 1;
    CHECK_NEAR(spread_plan_makespan(e, 2, 2, 2), 10, 1e-9);
    CHECK(spread_plan_makespan(e, 0, 2, 2) == 0);
}

static void plan_file(void)
{
    struct spread_entry e[2] = {entry(STUDY_FAN_REFERENCE, 1.5, 2), entry(STUDY_FAN_IMAGE, 0.25, 1)};
    struct spread_plan p = {.e = e, .n = 2, .total_cpu_s = 1.75}, back;
    char dir[] = "/tmp/test_spread_plan.XXXXXX", path[64];
    struct err err = {0};
    CHECK(mkdtemp(dir) != NULL);
    CHECK(fileio_write_text(dir, SPREAD_PLAN_FILE, spread_plan_text(&p), &err) == 0);
    snprintf(path, sizeof path, "%s/%s", dir, SPREAD_PLAN_FILE);
    CHECK(spread_plan_read(path, &back) == 0);
    CHECK(back.n == 2 && back.e[0].kind == STUDY_FAN_REFERENCE && back.e[1].kind == STUDY_FAN_IMAGE);
    CHECK(back.n == 2 && !strcmp(back.e[1].name, "b-img-0-00000.yaml") && back.e[1].processes == 1);
    CHECK_NEAR(back.total_cpu_s, 1.75, 1e-9);
    spread_plan_free(&back);
    unlink(path);
    rmdir(dir);
    CHECK(spread_plan_read(path, &back) < 0);
}

int main(void)
{
    names();
    makespan();
    plan_file();
    return check_report("test_spread_plan");
}
