/* compare_fixture: what test_compare and test_compare_suite share: a scratch folder under /tmp,
   job files written into it with SCENE standing for the checker scene's path, and its removal. */
#ifndef COMPARE_FIXTURE_H
#define COMPARE_FIXTURE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

struct compare_fixture {
    char dir[256];    /* the scratch folder */
    char scene[1024]; /* scenes/checker.yaml, absolute (the tests run from the repository) */
};

/* Make the scratch folder /tmp/<name>.XXXXXX. 0, or -1. */
static inline int compare_fixture_open(struct compare_fixture *fx, const char *name)
{
    char cwd[512];
    snprintf(fx->dir, sizeof fx->dir, "/tmp/%s.XXXXXX", name);
    if (!mkdtemp(fx->dir) || !getcwd(cwd, sizeof cwd))
        return -1;
    snprintf(fx->scene, sizeof fx->scene, "%s/scenes/checker.yaml", cwd);
    return 0;
}

/* Write text (each "SCENE" replaced by fx->scene) to fx->dir/name; the path, valid until the next
   call. */
static inline const char *compare_fixture_file(const struct compare_fixture *fx, const char *name,
                                               const char *text)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", fx->dir, name);
    FILE *f = fopen(path, "w");
    if (!f)
        return path;
    for (const char *p = text; *p; p++)
        if (!strncmp(p, "SCENE", 5)) {
            fputs(fx->scene, f);
            p += 4;
        } else {
            fputc(*p, f);
        }
    fclose(f);
    return path;
}

/* Remove the scratch folder and all in it. 0, or -1. */
static inline int compare_fixture_close(const struct compare_fixture *fx)
{
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", fx->dir);
    return system(cmd) == 0 ? 0 : -1;
}

#endif
