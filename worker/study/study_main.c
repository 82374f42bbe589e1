/* study_main: one driver for both kinds of compare job. */
#include "study_main.h"

#include <stdio.h>
#include <time.h>

#include "compare.h"
#include "compare_suite.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* A loaded compare job: a plain one (c) or a suite (s). */
struct loaded {
    struct compare *c;
    struct compare_suite *s;
};

static int load(const char *from, const char *path, struct loaded *l, struct err *e)
{
    if (compare_suite_is_suite(from))
        l->s = compare_suite_load_as(from, path, e);
    else
        l->c = compare_load_as(from, path, e);
    return l->c || l->s ? 0 : -1;
}

static const char *name_of(const struct loaded *l)
{
    return l->s ? l->s->name : l->c->name;
}

static void free_loaded(struct loaded *l)
{
    compare_suite_free(l->s);
    compare_free(l->c);
}

static int main_as(const char *from, const char *path, const struct run_opts *o, char *last, size_t n,
                   char *name, size_t name_n, int (*name_ok)(const char *name, void *arg), void *arg)
{
    struct err e = {0};
    struct loaded l = {0};
    char line[4096];
    double t0 = now_s();
    int rc = 2, loaded = load(from, path, &l, &e) == 0;
    if (loaded && name)
        snprintf(name, name_n, "%s", name_of(&l));
    if (loaded && name_ok && !name_ok(name_of(&l), arg)) {
        free_loaded(&l);
        return 2;
    }
    if (loaded)
        rc = l.s ? compare_suite_run(l.s, o, &e) : compare_run(l.c, o, &e);
    if (rc != 0) {
        if (rc == 1 && loaded) /* a render failure names the job; bad input names its file */
            err_prefix(&e, name_of(&l));
        err_format(&e, line, sizeof line);
    } else if (l.s) { /* each study's verdict warnings were printed as it finished (compare_run) */
        compare_suite_summary_line(l.s, now_s() - t0, o->out_dir, line, sizeof line);
    } else {
        compare_summary_line(l.c, now_s() - t0, o->out_dir, line, sizeof line);
    }
    if (!(rc == 1 && o->stop && *o->stop)) /* stopped (a signal, a queue claim gone): the caller says so */
        fprintf(stderr, "%s\n", line);
    if (last)
        snprintf(last, n, "%s", line);
    free_loaded(&l);
    return rc;
}

int study_main(const char *path, const struct run_opts *o, int (*name_ok)(const char *name, void *arg),
               void *arg)
{
    return main_as(path, path, o, NULL, 0, NULL, 0, name_ok, arg);
}

int study_main_as(const char *from, const char *path, const struct run_opts *o, char *last, size_t n,
                  char *name, size_t name_n)
{
    return main_as(from, path, o, last, n, name, name_n, NULL, NULL);
}
