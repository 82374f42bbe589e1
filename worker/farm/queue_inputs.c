/* queue_inputs: refuse a queued job's scene or reference that a symbolic link leads out of the queue. */
#include "queue_inputs.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* path made absolute (from the working directory) with ".", ".." and repeated slashes resolved as
   text, no link followed, into out. 0, or -1 when it does not fit. */
static int lexical(const char *path, char *out, size_t n)
{
    char buf[PATH_MAX * 2], cwd[PATH_MAX];
    if (path[0] != '/' && !getcwd(cwd, sizeof cwd))
        return -1;
    if (snprintf(buf, sizeof buf, "%s/%s", path[0] == '/' ? "" : cwd, path) >= (int)sizeof buf)
        return -1;
    size_t len = 0;
    for (char *save = NULL, *part = strtok_r(buf, "/", &save); part; part = strtok_r(NULL, "/", &save)) {
        if (!strcmp(part, "."))
            continue;
        if (!strcmp(part, "..")) {
            while (len > 0 && out[--len] != '/')
                ;
            continue;
        }
        size_t k = strlen(part);
        if (len + 1 + k + 1 > n)
            return -1;
        out[len++] = '/';
        memcpy(out + len, part, k);
        len += k;
    }
    if (len == 0)
        out[len++] = '/';
    out[len] = 0;
    return 0;
}

/* Whether path is dir or lies under it (both absolute, normalised). */
static int under(const char *path, const char *dir)
{
    size_t n = strlen(dir);
    if (n == 1) /* "/" */
        return 1;
    return !strncmp(path, dir, n) && (path[n] == '/' || path[n] == 0);
}

/* One input file: see queue_inputs_check. */
static int check_one(const char *dir_text, const char *dir_real, const char *key, const char *path,
                     const char *job_path, const int pos[2], struct err *e)
{
    char text[PATH_MAX], real[PATH_MAX];
    if (!path[0] || lexical(path, text, sizeof text) < 0 || !under(text, dir_text))
        return 0;
    if (!realpath(path, real)) /* missing: job_load said so, or it went meanwhile (the reader says) */
        return 0;
    if (under(real, dir_real))
        return 0;
    return err_set(e, job_path, pos[0], pos[1],
                   "%s: %s leaves the queue through a symbolic link (to %s): a queued job reads no file that "
                   "a link inside the queue points out of it (name the file itself)",
                   key, path, real);
}

int queue_inputs_check(const char *dir, const struct job *j, struct err *e)
{
    char dir_text[PATH_MAX], dir_real[PATH_MAX];
    if (lexical(dir, dir_text, sizeof dir_text) < 0 || !realpath(dir, dir_real))
        return 0;
    if (check_one(dir_text, dir_real, "scene", j->scene_path, j->path, job_at(j, "scene"), e) < 0 ||
        check_one(dir_text, dir_real, "reference", j->reference, j->path, job_at(j, "reference"), e) < 0)
        return -1;
    return 0;
}
