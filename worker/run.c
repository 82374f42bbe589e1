/* run: one job from its loaded settings to an image and its sidecar on disk. */
#include "run.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "fileio.h"
#include "limits.h"
#include "metrics.h"
#include "part.h"
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

/* Make dir (and its parents) for outputs about to be written; *made: whether dir itself was made
   here, so a failed write may remove it. A folder that was there already, or that another process
   made meanwhile, is never ours to remove. */
static int make_out_dir(const char *dir, int *made, struct err *e)
{
    char parent[2048];
    snprintf(parent, sizeof parent, "%s", dir);
    char *slash = strrchr(parent, '/');
    *made = 0;
    if (slash && slash != parent) {
        *slash = 0;
        if (run_mkdirs(parent, e) < 0)
            return -1;
    }
    *made = mkdir(dir, 0755) == 0;
    return run_mkdirs(dir, e);
}

/* Whether n is a temporary of the file named base: fileio_write_atomic's ".<base>.tmp.XXXXXX", or
   its own temporary of such a staging file, "..<base>.tmp.XXXXXX.tmp.YYYYYY". */
static int is_temp_of(const char *n, const char *base)
{
    size_t bl = strlen(base);
    if (n[0] != '.')
        return 0;
    const char *t = !strncmp(n + 1, base, bl)                  ? n + 1 + bl
                    : n[1] == '.' && !strncmp(n + 2, base, bl) ? n + 2 + bl
                                                               : NULL;
    if (!t || strncmp(t, ".tmp.", 5) != 0)
        return 0;
    size_t rest = strlen(t + 5);
    return t == n + 1 + bl ? rest == 6 : rest == 17 && !strncmp(t + 11, ".tmp.", 5);
}

/* Remove the temporaries that writers killed half-way left for path beside it (is_temp_of). Only
   the holder of the folder's lock may call it. */
static void remove_dead_temps(const char *path)
{
    char dir[2048];
    const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path;
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) : 1, slash ? path : ".");
    DIR *d = opendir(dir);
    if (!d)
        return;
    struct dirent *de;
    while ((de = readdir(d))) {
        if (is_temp_of(de->d_name, base)) {
            char dead[4096];
            snprintf(dead, sizeof dead, "%s/%s", dir, de->d_name);
            unlink(dead);
        }
    }
    closedir(d);
}

int run_out_lock(const char *dir, const char *const *paths)
{
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC), rc = -1;
    if (fd < 0)
        return -1;
    while ((rc = flock(fd, LOCK_EX)) < 0 && errno == EINTR)
        ;
    if (rc < 0) {
        close(fd);
        return -1;
    }
    for (int i = 0; paths && paths[i]; i++)
        remove_dead_temps(paths[i]);
    return fd;
}

void run_out_unlock(int fd)
{
    if (fd >= 0)
        close(fd); /* closing the last descriptor of the open folder releases the flock */
}

struct progress {
    const char *name;
    int enabled;
    int last_pct;
    void (*tick)(void *arg);
    void *tick_arg;
};

static void show_progress(void *arg, int done, int rows, double elapsed)
{
    struct progress *p = arg;
    if (p->tick)
        p->tick(p->tick_arg);
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

void run_paths(const struct job *j, const char *out_dir, char *dir, char *image, char *sidecar, size_t n)
{
    char stem[JOB_NAME_MAX];
    stem_of(j->output, stem, sizeof stem);
    snprintf(dir, n, "%s/%s", out_dir ? out_dir : "out", j->name);
    snprintf(image, n, "%s/%s/%s", out_dir ? out_dir : "out", j->name, j->output);
    snprintf(sidecar, n, "%s/%s/%s.json", out_dir ? out_dir : "out", j->name, stem);
}

static int is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

int run_load_reference(const struct job *j, int w, int h, struct rgb8 *ref, struct err *e)
{
    *ref = (struct rgb8){0};
    if (!j->reference[0])
        return 0;
    if (imgio_read(j->reference, ref, e) < 0) {
        char why[sizeof e->msg];
        snprintf(why, sizeof why, "%s", e->msg);
        return err_set(e, j->path, j->pos_reference[0], j->pos_reference[1], "reference: %s: %s",
                       j->reference, why);
    }
    if (ref->w != w || ref->h != h) {
        err_set(e, j->path, j->pos_reference[0], j->pos_reference[1],
                "reference: image is %dx%d but the job renders %dx%d", ref->w, ref->h, w, h);
        rgb8_free(ref);
        return -1;
    }
    return 0;
}

/* A staging name for path, unique to this writer: "<dir>/.<base>.tmp.XXXXXX" with six letters
   or digits from the pid and the time, shaped as fileio_write_atomic's temporaries so that a
   writer killed between staging and renaming leaves nothing for good (is_temp_of). */
static void staged_name(const char *path, char *out, size_t n)
{
    static const char alnum[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t x = rng_mix64((uint64_t)getpid() << 32 ^ (uint64_t)ts.tv_sec << 30 ^ (uint64_t)ts.tv_nsec);
    char suffix[7];
    for (int i = 0; i < 6; i++, x /= 62)
        suffix[i] = alnum[x % 62];
    suffix[6] = 0;
    const char *slash = strrchr(path, '/');
    int dl = slash ? (int)(slash - path) + 1 : 0;
    snprintf(out, n, "%.*s.%s.tmp.%s", dl, path, path + dl, suffix);
}

/* An error about writing the staging file `staged` names the final path instead. */
static void name_final(struct err *e, const char *staged, const char *final)
{
    char *at = strstr(e->msg, staged);
    if (!at)
        return;
    char msg[sizeof e->msg];
    snprintf(msg, sizeof msg, "%.*s%s%s", (int)(at - e->msg), e->msg, final, at + strlen(staged));
    snprintf(e->msg, sizeof e->msg, "%s", msg);
    if (!strcmp(e->file, staged))
        snprintf(e->file, sizeof e->file, "%s", final);
}

int run_write_outputs(const struct job *j, const struct run_opts *o, const float *rgb, int w, int h,
                      const struct farm_result *fr, const struct rgb8 *ref, int parts, struct run_result *rr,
                      struct err *e)
{
    char dir[2048], staged_image[2100], staged_sidecar[2100];
    struct rgb8 img = {0};
    char *json = NULL;
    int rc = -1, made_dir = 0, lock = -1;
    run_paths(j, o->out_dir, dir, rr->image_path, rr->sidecar_path, sizeof rr->image_path);
    if (make_out_dir(dir, &made_dir, e) < 0 || rgb8_alloc(&img, w, h, e) < 0)
        goto done;
    staged_name(rr->image_path, staged_image, sizeof staged_image);
    staged_name(rr->sidecar_path, staged_sidecar, sizeof staged_sidecar);
    const char *outs[] = {rr->image_path, rr->sidecar_path, NULL};
    lock = run_out_lock(dir, outs);
    image_float_to_rgb8(rgb, w, h, img.px);
    struct metrics m;
    int has_ref = ref && ref->px;
    if (has_ref && metrics_compare(ref, &img, &m, e) < 0)
        goto done;
    struct sidecar sc = {j, w, h, fr, has_ref ? &m : NULL, j->output, parts};
    if (!(json = sidecar_json(&sc))) {
        err_set(e, NULL, 0, 0, "out of memory writing the sidecar");
        goto done;
    }
    /* Both are written whole under staging names first, then renamed, the image first: a failure
       before the renames (a full disk, a size limit) leaves an earlier image and sidecar as they
       were. A killed writer's staged files and their temporaries go under the next one's lock. */
    if (imgio_write(staged_image, &img, j->format, e) < 0) {
        name_final(e, staged_image, rr->image_path);
        goto done;
    }
    if (fileio_write_atomic(staged_sidecar, json, strlen(json), e) < 0) {
        name_final(e, staged_sidecar, rr->sidecar_path);
        unlink(staged_image);
        goto done;
    }
    if (rename(staged_image, rr->image_path) < 0) {
        err_set(e, NULL, 0, 0, "cannot write %s: %s", rr->image_path, strerror(errno));
        unlink(staged_image);
        unlink(staged_sidecar);
        goto done;
    }
    if (rename(staged_sidecar, rr->sidecar_path) < 0) {
        err_set(e, NULL, 0, 0, "cannot write %s: %s", rr->sidecar_path, strerror(errno));
        unlink(staged_sidecar);
        unlink(rr->image_path); /* an image without its sidecar is not a finished job */
        goto done;
    }
    rc = 0;
done:
    run_out_unlock(lock);
    if (rc != 0 && made_dir)
        rmdir(dir); /* a failed write leaves no empty folder of ours (it fails when not empty) */
    free(json);
    rgb8_free(&img);
    return rc;
}

/* Resume: the outputs exist and were made from these very inputs. */
static int outputs_current(const struct job *j, const struct run_opts *o, struct run_result *rr)
{
    char dir[2048];
    if (j->hash == 0) /* a job not read from a file (no job_load): nothing to compare with */
        return 0;
    if (o->parts > 0) {
        part_path(j, o->out_dir, o->part, o->parts, rr->image_path, sizeof rr->image_path);
        rr->sidecar_path[0] = 0;
        return part_matches(rr->image_path, j, o->part, o->parts);
    }
    run_paths(j, o->out_dir, dir, rr->image_path, rr->sidecar_path, sizeof rr->image_path);
    return is_file(rr->image_path) && sidecar_matches(rr->sidecar_path, j->hash);
}

int run_job(const struct job *j, const struct run_opts *o, struct run_result *rr, struct err *e)
{
    struct scene_file sf = {0};
    struct sampler *pix = NULL, *light = NULL;
    struct rgb8 ref = {0};
    float *rgb = NULL;
    char dir[2048], image[2048], sidecar[2048];
    int rc = 2, made_dir = 0;
    memset(rr, 0, sizeof *rr);
    if (!o->force && outputs_current(j, o, rr)) {
        rr->skipped = 1;
        return 0;
    }
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
    if (run_load_reference(j, w, h, &ref, e) < 0)
        goto done;
    if (limits_check_samples(j, w, h, e) < 0 ||
        limits_check_memory("the framebuffer", (size_t)w * h * 3 * sizeof(float) + (size_t)w * h * 3, e) < 0)
        goto done;
    uint64_t pool_seed = rng_mix64(j->seed ^ 0x706f6f6cULL);
    if (!(pix = sampler_new(j->sampler, j->threshold, j->poisson_pool, pool_seed, e)) ||
        !(light = sampler_new(j->light_sampler, j->light_threshold, j->poisson_pool, pool_seed + 1, e))) {
        snprintf(e->file, sizeof e->file, "%s", j->path);
        goto done;
    }
    /* Nothing is made before the outputs are written: a failed or stopped render leaves no folder. */
    run_paths(j, o->out_dir, dir, image, sidecar, sizeof dir);
    if (limits_check_out_dir(dir, e) < 0)
        goto done;
    rc = 1;
    if (!(rgb = farm_framebuffer_new(w, h, e)))
        goto done;
    struct progress prog = {j->name, o->progress && !o->quiet, -1, o->tick, o->tick_arg};
    struct farm_job fj = {.scene = sf.scene,
                          .camera = &cam,
                          .rs = {w, h, j->max_depth, j->seed, !j->light_sampling},
                          .pixel = pix,
                          .light = light,
                          .processes = o->processes > 0 ? o->processes : j->processes,
                          .row_part = o->parts > 0 ? o->part : 0,
                          .row_parts = o->parts > 0 ? o->parts : 1,
                          .progress = show_progress,
                          .progress_arg = &prog,
                          .stop = o->stop};
    if (farm_render(&fj, rgb, &rr->farm, e) < 0) {
        if (prog.enabled)
            fprintf(stderr, "\n");
        goto done;
    }
    if (o->may_write && !o->may_write(o->tick_arg)) {
        err_set(e, NULL, 0, 0, "rendered, but another worker holds the job now: nothing written");
        goto done;
    }
    if (o->parts > 0) {
        part_path(j, o->out_dir, o->part, o->parts, rr->image_path, sizeof rr->image_path);
        rr->sidecar_path[0] = 0;
        if (make_out_dir(dir, &made_dir, e) < 0)
            goto done;
        const char *outs[] = {rr->image_path, NULL};
        int lock = run_out_lock(dir, outs);
        int wrote = part_write(rr->image_path, j, w, h, o->part, o->parts, rgb, &rr->farm, e);
        run_out_unlock(lock);
        if (wrote < 0)
            goto done;
    } else if (run_write_outputs(j, o, rgb, w, h, &rr->farm, &ref, 0, rr, e) < 0) {
        goto done;
    }
    rc = 0;
done:
    if (rc != 0 && made_dir)
        rmdir(dir); /* a part that failed to write leaves no empty folder of ours */
    rgb8_free(&ref);
    farm_framebuffer_free(rgb, rr->width, rr->height);
    sampler_free(pix);
    sampler_free(light);
    scene_file_free(&sf);
    return rc;
}

void run_print_summary(const struct job *j, const struct run_result *rr)
{
    const struct render_stats *t = &rr->farm.total;
    err_print("%s: %dx%d %s t=%g (%.0f spp mean), %d process%s, %.2f s -> %s\n", j->name, rr->width,
              rr->height, sampler_kind_name(j->sampler), j->threshold,
              t->pixels ? (double)t->samples / t->pixels : 0.0, rr->farm.processes,
              rr->farm.processes == 1 ? "" : "es", rr->farm.wall_s, rr->image_path);
}
