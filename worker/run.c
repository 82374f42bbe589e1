/* run: one job from its loaded settings to an image and its sidecar on disk. */
#include "run.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fileio.h"
#include "limits.h"
#include "metrics.h"
#include "scene_load.h"
#include "sidecar.h"

int run_mkdirs(const char *path, struct err *e)
{
    char buf[2048];
    snprintf(buf, sizeof buf, "%s", path);
    for (char *p = buf + 1;; p++) {
        if (*p == '/' || *p == 0) {
            char c = *p;
            *p = 0;
            if (mkdir(buf, 0755) < 0 && errno != EEXIST)
                return err_set(e, NULL, 0, 0, "cannot create directory %s: %s", buf, strerror(errno));
            struct stat st;
            if (stat(buf, &st) < 0 || !S_ISDIR(st.st_mode))
                return err_set(e, NULL, 0, 0, "cannot create directory %s: a file is in the way", buf);
            *p = c;
            if (!c)
                break;
        }
    }
    return 0;
}

struct progress {
    const char *name;
    int enabled;
    int last_pct;
};

static void show_progress(void *arg, int done, int rows, double elapsed)
{
    struct progress *p = arg;
    if (!p->enabled || rows == 0)
        return;
    int pct = (int)(100.0 * done / rows);
    if (pct == p->last_pct && done != rows)
        return;
    p->last_pct = pct;
    double eta = done > 0 ? elapsed * (rows - done) / done : 0;
    fprintf(stderr, "\r%s: %3d%% (%d/%d rows) %.1f s elapsed, ETA %.1f s   ", p->name, pct, done, rows,
            elapsed, eta);
    if (done == rows)
        fprintf(stderr, "\n");
}

static void stem_of(const char *file, char *out, size_t n)
{
    const char *dot = strrchr(file, '.');
    int len = dot && dot != file ? (int)(dot - file) : (int)strlen(file);
    snprintf(out, n, "%.*s", len, file);
}

int run_job(const struct job *j, const struct run_opts *o, struct run_result *rr, struct err *e)
{
    struct scene_file sf = {0};
    struct sampler *pix = NULL, *light = NULL;
    struct rgb8 img = {0}, ref = {0};
    float *rgb = NULL;
    char *json = NULL;
    int rc = 2, has_ref = 0;
    memset(rr, 0, sizeof *rr);

    if (scene_load(j->scene_path, &sf, e) < 0)
        goto done;
    int w = j->width;
    int h = j->height ? j->height : (int)lround(w / sf.aspect);
    if (h < 1)
        h = 1;
    if (h > IMAGE_MAX_SIDE) {
        err_set(e, j->path, 0, 0, "height: width / aspect gives %d rows (limit %d)", h, IMAGE_MAX_SIDE);
        goto done;
    }
    rr->width = w;
    rr->height = h;
    struct camera cam;
    if (camera_init(&cam, &sf.camera, (double)w / h, e) < 0) {
        snprintf(e->file, sizeof e->file, "%s", j->scene_path);
        goto done;
    }
    if (j->reference[0]) {
        if (imgio_read(j->reference, &ref, e) < 0) {
            char why[sizeof e->msg];
            snprintf(why, sizeof why, "%s", e->msg);
            err_set(e, j->path, j->pos_reference[0], j->pos_reference[1], "reference: %s: %s", j->reference, why);
            goto done;
        }
        if (ref.w != w || ref.h != h) {
            err_set(e, j->path, j->pos_reference[0], j->pos_reference[1],
                    "reference: image is %dx%d but the job renders %dx%d", ref.w, ref.h, w, h);
            goto done;
        }
        has_ref = 1;
    }
    if (limits_check_samples(j, w, h, e) < 0 ||
        limits_check_memory("the framebuffer", (size_t)w * h * 3 * sizeof(float) + (size_t)w * h * 3, e) < 0)
        goto done;
    uint64_t pool_seed = rng_mix64(j->seed ^ 0x706f6f6cULL);
    if (!(pix = sampler_new(j->sampler, j->threshold, j->poisson_pool, pool_seed, e)) ||
        !(light = sampler_new(j->light_sampler, j->light_threshold, j->poisson_pool, pool_seed + 1, e))) {
        snprintf(e->file, sizeof e->file, "%s", j->path);
        goto done;
    }
    const char *out_dir = o->out_dir ? o->out_dir : "out";
    char dir[2048], stem[JOB_NAME_MAX];
    snprintf(dir, sizeof dir, "%s/%s", out_dir, j->name);
    if (limits_check_out_dir(dir, e) < 0)
        goto done;
    rc = 1;
    if (!(rgb = farm_framebuffer_new(w, h, e)))
        goto done;
    struct progress prog = {j->name, o->progress && !o->quiet, -1};
    struct farm_job fj = {sf.scene, &cam, {w, h, j->max_depth, j->seed, !j->light_sampling}, pix, light,
                          o->processes > 0 ? o->processes : j->processes, 0, 1, show_progress, &prog};
    if (farm_render(&fj, rgb, &rr->farm, e) < 0) {
        if (prog.enabled)
            fprintf(stderr, "\n");
        goto done;
    }
    if (rgb8_alloc(&img, w, h, e) < 0)
        goto done;
    image_float_to_rgb8(rgb, w, h, img.px);
    struct metrics m;
    if (has_ref && metrics_compare(&ref, &img, &m, e) < 0)
        goto done;
    snprintf(rr->image_path, sizeof rr->image_path, "%s/%s", dir, j->output);
    stem_of(j->output, stem, sizeof stem);
    snprintf(rr->sidecar_path, sizeof rr->sidecar_path, "%s/%s.json", dir, stem);
    struct sidecar sc = {j, w, h, &rr->farm, has_ref ? &m : NULL, j->output};
    if (!(json = sidecar_json(&sc))) {
        err_set(e, NULL, 0, 0, "out of memory writing the sidecar");
        goto done;
    }
    if (imgio_write(rr->image_path, &img, j->format, e) < 0)
        goto done;
    if (fileio_write_atomic(rr->sidecar_path, json, strlen(json), e) < 0) {
        unlink(rr->image_path); /* an image without its sidecar is not a finished job */
        goto done;
    }
    rc = 0;
done:
    free(json);
    rgb8_free(&img);
    rgb8_free(&ref);
    farm_framebuffer_free(rgb, rr->width, rr->height);
    sampler_free(pix);
    sampler_free(light);
    scene_file_free(&sf);
    return rc;
}
