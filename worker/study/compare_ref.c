/* compare_ref: render a compare job's references into OUT/.cache/, or reuse the cached ones. */
#include "compare_ref.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fileio.h"
#include "image/imgio.h"
#include "base/hash.h"
#include "job/outdir.h"
#include "job/sidecar.h"
#include "scenefile/scene_load.h"

/* The cache key of a scene's reference: its scene file's and texture images' bytes, every setting that
   changes the reference's pixels, and the worker program's own bytes: a rebuilt renderer may draw other
   pixels, and its version string does not change with every commit. */
static int reference_key(const struct compare_scene *cs, uint64_t *key, struct err *e)
{
    const struct job *j = &cs->ref_job;
    struct err ignored;
    uint64_t h = HASH_FNV_OFFSET;
    fileio_hash("/proc/self/exe", 1u << 30, &h, &ignored); /* unreadable: the key lacks it */
    if (scene_hash_inputs(j->scene_path, &h, e) < 0)
        return -1;
    char text[512];
    int n = snprintf(
        text, sizeof text, "%dx%d %s %.17g %s %.17g depth %d seed %llu pool %d lights %d worker %s%s%s%s",
        cs->width, cs->height, sampler_kind_name(j->sampler), j->threshold,
        sampler_kind_name(j->light_sampler), j->light_threshold, j->max_depth, (unsigned long long)j->seed,
        j->poisson_pool, j->light_sampling, WORKER_VERSION, j->nee ? " nee" : "",
        j->dims_all ? " dims all" : "", job_roulette(j) ? " roulette" : "");
    *key = hash_bytes(h, text, (size_t)n);
    return 0;
}

/* The seconds a cached reference took to render and its samples per pixel, from its sidecar (0
   when unknown). */
static void cached_figures(const char *sidecar, struct compare_scene *cs)
{
    struct sidecar_info info;
    struct err e;
    int ok = sidecar_read(sidecar, &info, &e) == 0;
    cs->ref_wall_s = ok && isfinite(info.wall_s) ? info.wall_s : 0;
    cs->ref_spp = ok && isfinite(info.spp_mean) ? info.spp_mean : 0;
}

int compare_ref_prepare(struct compare *c, int s, const struct run_opts *o, struct err *e)
{
    struct compare_scene *cs = &c->scenes[s];
    if (cs->ref_kind != COMPARE_REF_SETTINGS)
        return 0;
    uint64_t key;
    if (reference_key(cs, &key, e) < 0)
        return 2;
    struct job j = cs->ref_job;
    snprintf(j.name, sizeof j.name, ".cache");
    /* linear radiance, as every error is measured in */
    j.format = IMG_EXR;
    snprintf(j.output, sizeof j.output, "ref-%s-%016llx.exr", cs->name, (unsigned long long)key);
    char dir[JOB_PATH_MAX], sidecar[JOB_PATH_MAX];
    outdir_paths(&j, o->out_dir, dir, cs->ref_path, sidecar, sizeof cs->ref_path);
    cs->ref_domain = IMG_LINEAR;
    struct rgbf img = {0};
    enum img_domain domain;
    struct err ignored;
    if (imgio_read_f(cs->ref_path, &img, &domain, &ignored) == 0 && img.w == cs->width &&
        img.h == cs->height) {
        image_f_free(&img);
        cs->ref_reused = 1;
        cached_figures(sidecar, cs);
        run_say(o, "%s: reference reused from cache %s (it took %.1f s to render)\n", cs->name, cs->ref_path,
                cs->ref_wall_s);
        return 0;
    }
    image_f_free(&img);
    run_say(o, "%s: rendering the reference (%s t=%g, light %s t=%g) into %s\n", cs->name,
            sampler_kind_name(j.sampler), j.threshold, sampler_kind_name(j.light_sampler), j.light_threshold,
            cs->ref_path);
    struct run_result rr;
    int rc = run_job(&j, o, &rr, e);
    if (rc != 0) {
        err_prefix(e, "reference");
        return rc;
    }
    cs->ref_wall_s = rr.procs.wall_s;
    cs->ref_spp = rr.procs.total.pixels ? (double)rr.procs.total.samples / rr.procs.total.pixels : 0;
    return 0;
}
