/* job_estimate: a job's cost from a pilot of a few pixels (worker JOB --dry-run). */
#include "job_estimate.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "base/clock.h"
#include "base/rng.h"
#include "job_limits.h"
#include "render/render.h"

/* This process's resident set in bytes (/proc/self/statm), 0 when unknown. */
static double resident_bytes(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    unsigned long long size = 0, resident = 0;
    if (!f)
        return 0;
    int ok = fscanf(f, "%llu %llu", &size, &resident) == 2;
    fclose(f);
    return ok ? (double)resident * (double)sysconf(_SC_PAGESIZE) : 0;
}

/* Pixels k of n of a w x h image, spread over it: one per band of rows, at golden-ratio steps
   across (a pixel's cost depends on what it sees). */
static void pilot_pixel(int k, int n, int w, int h, int *x, int *y)
{
    *y = (int)((k + 0.5) * h / n);
    *x = (int)(fmod((k + 0.5) * 0.6180339887498949, 1.0) * w);
}

/* A pilot's progress: pixels counted, and the paths it may trace next. */
struct pilot_run {
    double budget_s, spent_s;  /* CPU seconds: the budget, and all spent (re-renders too) */
    size_t cap;                /* paths the next render_pixel_paths may trace */
    double paths;              /* paths traced by every call */
    int k;                     /* pixels counted */
    double drawn, traced;      /* the counted pixels' camera samples, and those traced */
    double counted_s, pixel_s; /* their CPU seconds, and those scaled to whole pixels */
};

/* Render pixel (x, y) of the pilot at most p->cap paths, and count it when it is whole or the
   budget is spent (a cut pixel's time scaled to all its samples); else leave it to be rendered
   again with more paths. The cap starts at one path and grows at most 8 times a call, to what
   the budget left would pay at the cost per path so far: however costly a path is (a whole pixel
   of 100000 stacked pyramids took 22 s), the pilot stays near its budget. */
static void pilot_step(struct pilot_run *p, struct render_ctx *ctx, int x, int y, struct render_stats *st)
{
    float rgb[3];
    double t0 = clock_s(CLOCK_THREAD_CPUTIME_ID);
    size_t all = render_pixel_paths(ctx, x, y, p->cap, rgb, st);
    double dt = clock_s(CLOCK_THREAD_CPUTIME_ID) - t0;
    size_t done = all < p->cap ? all : p->cap;
    p->spent_s += dt;
    p->paths += (double)done;
    double per_path = p->paths > 0 ? p->spent_s / p->paths : 0;
    double afford = per_path > 0 ? (p->budget_s - p->spent_s) / per_path : HUGE_VAL; /* paths the rest pays */
    size_t grown = p->cap > SIZE_MAX / 8 ? SIZE_MAX : p->cap * 8;
    size_t cap = afford < (double)grown ? (afford < 1 ? 1 : (size_t)afford) : grown;
    if (done < all && cap > done) {
        p->cap = cap; /* again, with more of its paths */
        return;
    }
    p->cap = cap;
    p->k++;
    p->drawn += (double)all;
    p->traced += (double)done;
    p->counted_s += dt;
    p->pixel_s += done ? dt * (double)all / (double)done : dt;
}

/* Render the pilot pixels of est's image with the samplers; fill est's per-sample figures. */
static int pilot(const struct job *j, const struct scene_file *sf, double budget_s, struct job_estimate *est,
                 struct err *e)
{
    struct camera cam;
    struct sampler *pix = NULL, *light = NULL;
    struct render_ctx *ctx = NULL;
    int rc = -1;
    if (camera_init(&cam, &sf->camera, (double)est->width / est->height, e) < 0) {
        snprintf(e->file, sizeof e->file, "%s", j->scene_path);
        return -1;
    }
    uint64_t pool_seed = rng_mix64(j->seed ^ 0x706f6f6cULL); /* run_job's: the same pools */
    const struct render_settings rs = {est->width,         est->height, j->max_depth, j->seed,
                                       !j->light_sampling, j->nee,      j->dims_all,  job_roulette(j)};
    if (!(pix = sampler_new(j->sampler, j->threshold, j->poisson_pool, pool_seed, e)) ||
        !(light = sampler_new(j->light_sampler, j->light_threshold, j->poisson_pool, pool_seed + 1, e))) {
        snprintf(e->file, sizeof e->file, "%s", j->path);
        goto done;
    }
    if (!(ctx = render_ctx_new(sf->scene, &cam, &rs, pix, light, e)))
        goto done;
    struct render_stats st;
    render_stats_init(&st);
    long pixels = (long)est->width * est->height;
    int n = pixels < JOB_ESTIMATE_PILOT_PIXELS ? (int)pixels : JOB_ESTIMATE_PILOT_PIXELS;
    struct pilot_run p = {.budget_s = budget_s, .cap = 1};
    while (p.k < n && (p.k == 0 || p.spent_s < budget_s)) {
        int x, y;
        pilot_pixel(p.k, n, est->width, est->height, &x, &y);
        pilot_step(&p, ctx, x, y, &st);
    }
    est->pilot_pixels = p.k;
    est->pilot_samples = p.drawn;
    est->pilot_traced = p.traced;
    /* the renderers share the scene's textures (read-only pages after fork): counted once */
    for (int i = 0; i < sf->scene->n_images; i++)
        est->texture_bytes += (double)sf->scene->images[i].w * sf->scene->images[i].h * 3;
    est->process_bytes = fmax(0, resident_bytes() - est->texture_bytes);
    est->spp_mean = p.drawn / p.k;
    est->samples = est->spp_mean * (double)pixels;
    est->ns_per_sample = p.traced ? p.counted_s * 1e9 / p.traced : 0;
    est->cpu_s = p.pixel_s / p.k * (double)pixels;
    rc = 0;
done:
    render_ctx_free(ctx);
    sampler_free(pix);
    sampler_free(light);
    return rc;
}

int job_estimate(const struct job *j, const struct scene_file *sf, int processes, double budget_s,
                 struct job_estimate *out, struct err *e)
{
    struct scene_file own = {0};
    memset(out, 0, sizeof *out);
    if (!sf) {
        if (scene_load(j->scene_path, &own, e) < 0)
            return -1;
        sf = &own;
    }
    int rc = -1;
    out->width = j->width;
    out->height = job_height(j, sf->aspect);
    out->processes = processes > 0 ? processes : j->processes;
    if (out->height > IMAGE_MAX_SIDE)
        err_set(e, j->path, j->pos_width[0], j->pos_width[1],
                "width: %d / the camera's aspect %g gives %d rows (limit %d); give height:", j->width,
                sf->aspect, out->height, IMAGE_MAX_SIDE);
    else if (job_limits_samples(j, out->width, out->height, e) == 0) {
        out->framebuffer_bytes = (double)out->width * out->height * (3 * sizeof(float) + 3);
        rc = pilot(j, sf, budget_s, out, e);
    }
    scene_file_free(&own);
    return rc;
}

double job_estimate_memory(const struct job_estimate *est)
{
    return est->framebuffer_bytes + est->texture_bytes + est->processes * est->process_bytes;
}
