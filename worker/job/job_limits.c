/* job_limits: up-front checks of job size, memory and the output folder. */
#include "job_limits.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "run.h"

int job_limits_samples(const struct job *j, int width, int height, struct err *e)
{
    double per_pixel = (double)sampler_capacity(j->sampler, j->threshold);
    double total = per_pixel * width * height;
    if (total <= LIMITS_MAX_JOB_SAMPLES)
        return 0;
    return err_set(e, j->path, j->pos_threshold[0], j->pos_threshold[1],
                   "threshold: %dx%d pixels at up to %.0f samples each is %.3g samples (limit %.3g)", width,
                   height, per_pixel, total, LIMITS_MAX_JOB_SAMPLES);
}

/* MemAvailable in bytes, or 0 when unknown. */
static size_t mem_available(void)
{
    FILE *f = fopen("/proc/meminfo", "r");
    if (!f)
        return 0;
    char line[256];
    unsigned long long kb = 0;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "MemAvailable: %llu kB", &kb) == 1)
            break;
    fclose(f);
    return (size_t)kb * 1024;
}

int job_limits_memory(const char *what, size_t bytes, struct err *e)
{
    size_t avail = mem_available();
    if (avail == 0 || bytes <= avail / 2)
        return 0;
    return err_set(e, NULL, 0, 0, "%s needs %zu MB, over half of the %zu MB of memory available", what,
                   bytes >> 20, avail >> 20);
}

int job_limits_out_dir(const char *dir, struct err *e)
{
    char p[2048];
    snprintf(p, sizeof p, "%s", dir);
    for (;;) {
        struct stat st;
        if (stat(p, &st) == 0) {
            if (!S_ISDIR(st.st_mode))
                return err_set(e, NULL, 0, 0, "cannot create directory %s: a file is in the way", p);
            if (access(p, W_OK | X_OK) < 0)
                return err_set(e, NULL, 0, 0, "cannot write to output directory %s: %s", p, strerror(errno));
            return 0;
        }
        if ((errno != ENOENT && errno != ENOTDIR) || !strcmp(p, "."))
            return err_set(e, NULL, 0, 0, "cannot create directory %s: %s", dir, strerror(errno));
        /* missing, but a name is there: a dangling symbolic link, where mkdir fails (EEXIST) */
        if (lstat(p, &st) == 0)
            return err_set(e, NULL, 0, 0, "cannot create directory %s: a file is in the way (%s)", p,
                           S_ISLNK(st.st_mode) ? "a symbolic link to nothing" : "not a directory");
        char *slash = strrchr(p, '/');
        if (!slash)
            snprintf(p, sizeof p, ".");
        else
            slash[slash == p] = '\0'; /* "/x" -> "/", "a/b" -> "a" */
    }
}
