/* job_limits: up-front checks of job size and memory (the output folder's: outdir_check). */
#include "job_limits.h"

#include <stdio.h>

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
