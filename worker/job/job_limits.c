/* job_limits: up-front checks of job size and memory (the output folder's: outdir_check). */
#include "job_limits.h"

#include <stdio.h>

/* A Poisson pool of sampler (kind, t): poisson_pool x its largest set within the limit. */
static int pool_points(const struct job *j, enum sampler_kind kind, double t, struct err *e)
{
    if (!sampler_kind_has(kind, SAMPLER_POOLED) || j->spec.poisson_pool == 0)
        return 0;
    double per_set = (double)sampler_capacity(kind, t), total = per_set * j->spec.poisson_pool;
    if (total <= LIMITS_MAX_POOL_POINTS)
        return 0;
    return err_set(e, j->path, job_at(j, "poisson_pool")[0], job_at(j, "poisson_pool")[1],
                   "poisson_pool: %d sets of up to %.0f points (%s t=%g) is %.3g points, held in memory "
                   "(limit %.3g); take a smaller pool or a larger threshold",
                   j->spec.poisson_pool, per_set, sampler_kind_name(kind), t, total, LIMITS_MAX_POOL_POINTS);
}

int job_limits_samples(const struct job *j, int width, int height, struct err *e)
{
    double per_pixel = (double)sampler_capacity(j->spec.pixel.kind, j->spec.pixel.threshold);
    double total = per_pixel * width * height;
    if (total > LIMITS_MAX_JOB_SAMPLES)
        return err_set(e, j->path, job_at(j, "threshold")[0], job_at(j, "threshold")[1],
                       "threshold: %dx%d pixels at up to %.0f samples each is %.3g samples (limit %.3g)",
                       width, height, per_pixel, total, LIMITS_MAX_JOB_SAMPLES);
    /* each pixel draws a fresh Poisson set per light, whole, however few of its points it takes */
    if (j->spec.light_sampling && sampler_kind_has(j->spec.light.kind, SAMPLER_POOLED) &&
        j->spec.poisson_pool == 0) {
        double per_light = (double)sampler_capacity(j->spec.light.kind, j->spec.light.threshold);
        double points = per_light * width * height;
        if (points > LIMITS_MAX_JOB_SAMPLES)
            return err_set(e, j->path, job_at(j, "light_threshold")[0], job_at(j, "light_threshold")[1],
                           "light_threshold: %g draws a fresh %s set of up to %.0f points per pixel and "
                           "light, %.3g points at %dx%d (limit %.3g); take a larger light_threshold, a "
                           "poisson_pool or another light_sampler",
                           j->spec.light.threshold, sampler_kind_name(j->spec.light.kind), per_light, points,
                           width, height, LIMITS_MAX_JOB_SAMPLES);
    }
    if (pool_points(j, j->spec.pixel.kind, j->spec.pixel.threshold, e) < 0)
        return -1;
    return j->spec.light_sampling ? pool_points(j, j->spec.light.kind, j->spec.light.threshold, e) : 0;
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
