/* job_fixture: job files written for the job tests (test_job.c, test_jobfile.c): a temporary
   folder, the checker scene's absolute path, and jobs on that scene written there and opened. */
#ifndef JOB_FIXTURE_H
#define JOB_FIXTURE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "job/jobfile.h"

struct job_fixture {
    char dir[64];     /* /tmp/<test>_XXXXXX, made by job_fixture_init */
    char scene[1024]; /* scenes/checker.yaml, absolute */
};

/* Make x's folder for the test `name` and find the checker scene (the tests run from the
   repository's root). 0, or -1 when either fails. */
static inline int job_fixture_init(struct job_fixture *x, const char *name)
{
    snprintf(x->dir, sizeof x->dir, "/tmp/%s_XXXXXX", name);
    if (!mkdtemp(x->dir) || !getcwd(x->scene, sizeof x->scene - 32))
        return -1;
    strcat(x->scene, "/scenes/checker.yaml");
    return 0;
}

/* Write text as x's folder/name; its path into path (n bytes). */
static inline void job_fixture_put(const struct job_fixture *x, const char *name, const char *text,
                                   char *path, size_t n)
{
    snprintf(path, n, "%s/%s", x->dir, name);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

/* Write "scene: <the checker scene>\n" + extra as x's folder/name (its path into path, n bytes)
   and jobfile_open it into f: its result (jobfile_close f after either). */
static inline int job_fixture_open(const struct job_fixture *x, const char *name, const char *extra,
                                   char *path, size_t n, struct jobfile *f, struct err *e)
{
    char text[1200];
    snprintf(text, sizeof text, "scene: %s\n%s", x->scene, extra);
    job_fixture_put(x, name, text, path, n);
    return jobfile_open(f, path, path, e);
}

#endif
