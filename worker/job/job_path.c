/* job_path: the files a job names: paths relative to the job file, a scene: value's places
   (a bare name looked up in several), and a "did you mean" when nothing is there. */
#include "job_path.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "scenefile/yamlx.h"

enum { HINT_NAME_MAX = 256, HINT_MAX_ENTRIES = 4096 };

/* The entry of folder dir nearest to name (ystr_nearest) into out, among its first HINT_MAX_ENTRIES:
   with stems, the *.yaml files by their stems. 1 when one is near, else 0 and out is "". */
static int nearest_entry(const char *dir, const char *name, int stems, char *out, size_t n)
{
    out[0] = 0;
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    char(*names)[HINT_NAME_MAX] = malloc(HINT_MAX_ENTRIES * sizeof *names);
    const char **list = malloc(HINT_MAX_ENTRIES * sizeof *list);
    int count = 0;
    struct dirent *de;
    for (int seen = 0; names && list && seen < HINT_MAX_ENTRIES && (de = readdir(d)); seen++) {
        size_t len = strlen(de->d_name);
        if (de->d_name[0] == '.' || len >= HINT_NAME_MAX)
            continue;
        if (stems) {
            if (len <= 5 || strcmp(de->d_name + len - 5, ".yaml") != 0)
                continue;
            len -= 5;
        }
        memcpy(names[count], de->d_name, len);
        names[count][len] = 0;
        list[count] = names[count];
        count++;
    }
    closedir(d);
    const char *near = count ? ystr_nearest(name, list, count) : NULL;
    if (near)
        snprintf(out, n, "%s", near);
    free(names);
    free(list);
    return near != NULL;
}

void job_path_dir(const char *path, char *out, size_t n)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(out, n, ".");
    else if (slash == path)
        snprintf(out, n, "/");
    else
        snprintf(out, n, "%.*s", (int)(slash - path), path);
}

void job_path_resolve(const char *base, const char *rel, char *out, size_t n)
{
    if (rel[0] == '/') {
        snprintf(out, n, "%s", rel);
        return;
    }
    char dir[JOB_PATH_MAX];
    job_path_dir(base, dir, sizeof dir);
    if (strcmp(dir, ".") == 0)
        snprintf(out, n, "%s", rel);
    else
        snprintf(out, n, "%s/%s", dir, rel);
}

int job_path_is_file(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0 && S_ISREG(st.st_mode);
}

/* The scenes shipped with the program: ../scenes beside the binary (a checkout's bin/worker) and
   ../share/worker/scenes (`make install`); how many (0 when /proc/self/exe cannot be read). */
static int shipped_scene_dirs(char dirs[2][JOB_PATH_MAX])
{
    char exe[JOB_PATH_MAX];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len <= 0 || len >= (ssize_t)sizeof exe - 1)
        return 0;
    exe[len] = 0;
    char bin[JOB_PATH_MAX], top[JOB_PATH_MAX];
    job_path_dir(exe, bin, sizeof bin);
    job_path_dir(bin, top, sizeof top);
    const char *sep = strcmp(top, "/") ? "/" : "";
    snprintf(dirs[0], JOB_PATH_MAX, "%.*s%sscenes", JOB_PATH_MAX - 32, top, sep);
    snprintf(dirs[1], JOB_PATH_MAX, "%.*s%sshare/worker/scenes", JOB_PATH_MAX - 32, top, sep);
    return 2;
}

/* The folders a bare scene name is looked up in, in order: the job file's own places first, so
   that a job means the same scene wherever the worker runs from (a queue's scenes/ beside its
   jobs wins over the worker's folder), then the current folder, then the shipped scenes. */
enum { N_BARE = 5 };
static int bare_dirs(const struct job *j, char dirs[N_BARE][JOB_PATH_MAX])
{
    job_path_resolve(j->path, "scenes", dirs[0], JOB_PATH_MAX);
    job_path_resolve(j->path, "../scenes", dirs[1], JOB_PATH_MAX);
    snprintf(dirs[2], JOB_PATH_MAX, "scenes");
    return 3 + shipped_scene_dirs(dirs + 3);
}

int job_path_scene(struct job *j, const char *val, char *tried, size_t n)
{
    tried[0] = 0;
    if (!strchr(val, '/') && !strchr(val, '.')) {
        char dirs[N_BARE][JOB_PATH_MAX], cand[N_BARE][JOB_PATH_MAX];
        int nc = bare_dirs(j, dirs);
        for (int i = 0; i < nc; i++)
            snprintf(cand[i], JOB_PATH_MAX, "%.*s/%s.yaml", JOB_PATH_MAX / 2, dirs[i], val);
        for (int i = 0; i < nc; i++)
            if (job_path_is_file(cand[i])) {
                snprintf(j->scene_path, sizeof j->scene_path, "%s", cand[i]);
                return 0;
            }
        snprintf(j->scene_path, sizeof j->scene_path, "%s", cand[0]);
        /* the other places looked in, each once */
        size_t used = 0;
        for (int i = 1; i < nc && used < n; i++) {
            int seen = 0;
            for (int k = 0; k < i; k++)
                seen |= strcmp(cand[k], cand[i]) == 0;
            if (!seen)
                used +=
                    (size_t)snprintf(tried + used, n - used, "%s%s", used ? " or " : " (nor at ", cand[i]);
        }
        if (used && used < n)
            snprintf(tried + used, n - used, ")");
        return -1;
    }
    job_path_resolve(j->path, val, j->scene_path, sizeof j->scene_path);
    return job_path_is_file(j->scene_path) ? 0 : -1;
}

const char *job_path_scene_hint(const struct job *j, const char *val, char *buf, size_t n)
{
    char near[256], dir[JOB_PATH_MAX];
    const char *slash = strrchr(j->scene_path, '/');
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - j->scene_path) : 1, slash ? j->scene_path : ".");
    if (!strchr(val, '/') && !strchr(val, '.')) { /* a bare name: a stem in any folder looked in */
        char dirs[N_BARE][JOB_PATH_MAX];
        near[0] = 0;
        for (int k = 0, nd = bare_dirs(j, dirs); k < nd && !near[0]; k++)
            nearest_entry(dirs[k], val, 1, near, sizeof near);
        if (!near[0])
            return "";
        snprintf(buf, n, " (did you mean \"%s\"?)", near);
        return buf;
    }
    const char *base = strrchr(val, '/');
    base = base ? base + 1 : val;
    if (!nearest_entry(dir, base, 0, near, sizeof near))
        return "";
    snprintf(buf, n, " (did you mean %.*s%s?)", (int)(base - val), val, near);
    return buf;
}
