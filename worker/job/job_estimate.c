/* job_estimate: a job's samples, memory and cost (the cost model's) without rendering it
   (worker JOB --dry-run). */
#include "job_estimate.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "job_limits.h"

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

/* One render process's buffers for j's point sets, which the pilot does not hold: the pixel set, each
   light's stream, the padded slots of sampler_dims: all (render_ctx.c's: 2 + 4 a bounce, twice a
   set each, 16 bounces and 256 MB at most). */
static double set_bytes(const struct job *j, const struct scene_file *sf)
{
    const double pixel =
        (double)sampler_capacity(j->spec.pixel.kind, j->spec.pixel.threshold) * sizeof(struct pt2);
    const double light =
        (double)sampler_capacity(j->spec.light.kind, j->spec.light.threshold) * sizeof(struct pt2);
    double dims = 0;
    if (j->spec.dims_all)
        dims = fmin((2.0 + 4.0 * (j->spec.max_depth < 16 ? j->spec.max_depth : 16)) * 2 * pixel,
                    256.0 * (1 << 20));
    return pixel + (j->spec.light_sampling ? light * sf->scene->n_lights : 0) + dims;
}

int job_estimate(const struct job *j, const struct scene_file *sf, int processes, struct cost_model *m,
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
    out->width = j->spec.width;
    out->height = job_height(j, sf->aspect);
    out->processes = processes > 0 ? processes : j->processes;
    if (out->height > IMAGE_MAX_SIDE)
        err_set(e, j->path, job_at(j, "width")[0], job_at(j, "width")[1],
                "width: %d / the camera's aspect %g gives %d rows (limit %d); give height:", j->spec.width,
                sf->aspect, out->height, IMAGE_MAX_SIDE);
    else if (job_limits_samples(j, out->width, out->height, e) == 0) {
        out->framebuffer_bytes = (double)out->width * out->height * (3 * sizeof(float) + 3);
        rc = cost_model_estimate(m, j, sf, out->width, out->height, &out->cost, e);
    }
    if (rc == 0) {
        out->spp_mean = out->cost.spp_mean;
        out->samples = out->cost.samples;
        out->cpu_s = out->cost.cpu_s;
        /* the renderers share the scene's textures (read-only pages after fork): counted once */
        for (int i = 0; i < sf->scene->n_images; i++)
            out->texture_bytes += (double)sf->scene->images[i].w * sf->scene->images[i].h * 3;
        out->process_bytes = fmax(0, resident_bytes() - out->texture_bytes) + set_bytes(j, sf);
    }
    scene_file_free(&own);
    return rc;
}

int job_estimate_expect(const struct job *j, const struct scene_file *sf, struct cost_model *m, struct err *e)
{
    return cost_model_expect(m, j, sf, j->spec.width, job_height(j, sf->aspect), e);
}

double job_estimate_memory(const struct job_estimate *est)
{
    return est->framebuffer_bytes + est->texture_bytes + est->processes * est->process_bytes;
}
