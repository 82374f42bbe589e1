/* run_out: a job's outputs written into its folder (outdir) under the folder's lock: image and
   sidecar atomically, or a part file. */
#include "run_out.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/fileio.h"
#include "image/imgio.h"
#include "image/metrics.h"
#include "outdir.h"
#include "part.h"
#include "sidecar.h"

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

int run_out_lock_outputs(const char *dir, const char *const *paths, const struct run_opts *o, int *lock,
                         struct err *e)
{
    *lock = outdir_lock(dir, paths, o->stop, o->lock_wait_s);
    if (*lock == OUTDIR_WAITED_OUT && (!o->may_write || o->may_write(o->tick_arg, dir)))
        err_print("%s/: its lock has been held for over %g s (a lease timeout) by a writer that is stopped "
                  "or hung: writing without it\n",
                  dir, o->lock_wait_s);
    if (*lock == -1 && (errno == ELOOP || errno == ENOTDIR))
        return err_set(e, NULL, 0, 0, "%s is a symbolic link: outputs are never written through one", dir);
    if (*lock == OUTDIR_STOPPED)
        return err_set(e, NULL, 0, 0, "stopped while waiting for another writer of %s/: nothing written",
                       dir);
    if (!o->may_write || o->may_write(o->tick_arg, dir))
        return 0;
    return err_set(e, NULL, 0, 0,
                   "rendered, but it may not write %s/ now (another worker holds the job, or the folder is "
                   "another job's): nothing written",
                   dir);
}

int run_out_still_held(const struct run_opts *o, const char *dir, struct err *e)
{
    if (!o->still_held || o->still_held(o->tick_arg))
        return 0;
    return err_set(e, NULL, 0, 0, "the claim was taken over while it wrote %s/: nothing written", dir);
}

/* The EXR header's string attributes for j (nothing that depends on the process count or the
   output folder: the file's bytes do not). texts holds their values. */
static size_t exr_attrs(const struct job *j, struct img_attr *a, char texts[][160])
{
    const char *slash = strrchr(j->scene_path, '/');
    snprintf(texts[0], 160, "%s", slash ? slash + 1 : j->scene_path);
    snprintf(texts[1], 160, "%s t=%.17g", sampler_kind_name(j->sampler), j->threshold);
    snprintf(texts[2], 160, "%s t=%.17g", sampler_kind_name(j->light_sampler), j->light_threshold);
    snprintf(texts[3], 160, "%llu", (unsigned long long)j->seed);
    snprintf(texts[4], 160, "%d", j->max_depth);
    snprintf(texts[5], 160, "worker %s", WORKER_VERSION);
    const struct img_attr list[] = {{"job", j->name},           {"scene", texts[0]}, {"sampler", texts[1]},
                                    {"lightSampler", texts[2]}, {"seed", texts[3]},  {"maxDepth", texts[4]},
                                    {"software", texts[5]}};
    memcpy(a, list, sizeof list);
    return sizeof list / sizeof *list;
}

/* Score the framebuffer fb (its 8-bit conversion img when the reference holds 8-bit display
   values) against ref into rr. 0 or -1 with e filled. */
static int score(const struct rgbf *fb, const struct rgb8 *img, const struct rgbf *ref,
                 enum img_domain domain, struct run_result *rr, struct err *e)
{
    struct rgbf disp = {0};
    int rc = domain == IMG_LINEAR                   ? metrics_compare_f(ref, fb, 1, &rr->error, e)
             : image_f_from_rgb8(img, &disp, e) < 0 ? -1
                                                    : metrics_compare_f(ref, &disp, 1, &rr->error, e);
    image_f_free(&disp);
    rr->has_error = rc == 0;
    rr->error_domain = domain;
    return rc;
}

int run_out_write(const struct job *j, const struct run_opts *o, const float *rgb, int w, int h,
                  const struct procs_result *fr, const struct rgbf *ref, enum img_domain ref_domain,
                  int parts, struct run_result *rr, struct err *e)
{
    char dir[2048], staged[3][2100], attr_text[6][160];
    const char *final[3];
    struct img_attr attrs[8];
    struct rgb8 img = {0};
    struct rgbf fb = {w, h, (float *)rgb};
    char *json = NULL;
    int rc = -1, made_dir = 0, lock = -1, n = 0;
    int is_float = imgio_is_float(j->format), has_ref = ref && ref->px;
    outdir_paths(j, o->out_dir, dir, rr->image_path, rr->sidecar_path, sizeof rr->image_path);
    outdir_float_path(j, o->out_dir, rr->float_path, sizeof rr->float_path);
    if (outdir_mkdirs(dir, &made_dir, e) < 0 ||
        ((!is_float || (has_ref && ref_domain == IMG_DISPLAY8)) && image_alloc(&img, w, h, e) < 0))
        goto done;
    final[n++] = rr->image_path;
    if (rr->float_path[0])
        final[n++] = rr->float_path;
    final[n++] = rr->sidecar_path;
    for (int i = 0; i < n; i++)
        outdir_staged_name(final[i], staged[i], sizeof staged[i]);
    const char *outs[] = {final[0], final[1], n > 2 ? final[2] : NULL, NULL};
    if (run_out_lock_outputs(dir, outs, o, &lock, e) < 0)
        goto done;
    if (img.px)
        image_float_to_rgb8(rgb, w, h, img.px);
    rr->has_error = rr->has_display_error = 0;
    if (has_ref && score(&fb, &img, ref, ref_domain, rr, e) < 0)
        goto done;
    if (o->ref_display && img.px) {
        if (metrics_display_compare(o->ref_display, &img, &rr->display_error, e) < 0)
            goto done;
        rr->has_display_error = 1;
    }
    struct sidecar sc = {j, w, h, fr, rr->has_error ? &rr->error : NULL, ref_domain, j->output, parts};
    if (!(json = sidecar_json(&sc))) {
        err_set(e, NULL, 0, 0, "out of memory writing the sidecar");
        goto done;
    }
    /* All are written whole under staging names first: a failure before the renames (a full disk,
       a size limit) leaves the earlier outputs as they were. Then the earlier sidecar goes, the
       image and its float copy are renamed, the sidecar last: a reader (or a writer killed at any
       step) sees the earlier outputs, images without a sidecar (not finished: rendered again), or
       the new ones, never a new image beside an earlier sidecar (issue 21, defect 6). A killed
       writer's staged files and their temporaries go under the next one's lock. */
    size_t nattrs = exr_attrs(j, attrs, attr_text);
    int k = 0, wrote = is_float ? imgio_write_f(staged[0], &fb, j->format, attrs, nattrs, e)
                                : imgio_write(staged[0], &img, j->format, e);
    if (wrote == 0 && n == 3) /* the float copy */
        wrote = imgio_write_f(staged[++k], &fb, IMG_EXR, attrs, nattrs, e);
    if (wrote == 0)
        wrote = fileio_write_atomic(staged[++k], json, strlen(json), e);
    if (wrote < 0) {
        name_final(e, staged[k], final[k]);
        while (k-- > 0)
            unlink(staged[k]);
        goto done;
    }
    /* a writer stopped (SIGSTOP) until its claim was taken over renames nothing, lock or not */
    int failed = run_out_still_held(o, dir, e) < 0;
    if (!failed && unlink(rr->sidecar_path) < 0 && errno != ENOENT)
        failed = err_set(e, NULL, 0, 0, "cannot write %s: %s", rr->sidecar_path, strerror(errno)) < 0;
    for (int i = 0; i < n; i++) {
        /* a claim taken over between renames: what is renamed stays, without a sidecar */
        if (failed || (i > 0 && run_out_still_held(o, dir, e) < 0)) {
            for (int r = i; r < n; r++)
                unlink(staged[r]);
            goto done;
        }
        if (rename(staged[i], final[i]) == 0)
            continue;
        /* an image without its sidecar is not a finished job: undo the renames done */
        err_set(e, NULL, 0, 0, "cannot write %s: %s", final[i], strerror(errno));
        for (int r = 0; r < n; r++)
            unlink(r < i ? final[r] : staged[r]);
        goto done;
    }
    rr->black = image_float_black(rgb, w, h);
    rc = 0;
done:
    outdir_unlock(lock);
    if (rc != 0 && made_dir)
        rmdir(dir); /* a failed write leaves no empty folder of ours (it fails when not empty) */
    free(json);
    image_free(&img);
    return rc;
}

int run_out_write_part(const struct job *j, const struct run_opts *o, const float *rgb, int w, int h,
                       const struct procs_result *fr, struct run_result *rr, struct err *e)
{
    char dir[2048];
    int made_dir = 0, lock = -1, rc = -1;
    outdir_dir(o->out_dir, j->name, dir, sizeof dir);
    outdir_part_path(j, o->out_dir, o->part, o->parts, rr->image_path, sizeof rr->image_path);
    rr->sidecar_path[0] = 0;
    const char *outs[] = {rr->image_path, NULL};
    if (outdir_mkdirs(dir, &made_dir, e) == 0 && run_out_lock_outputs(dir, outs, o, &lock, e) == 0)
        rc = part_write(rr->image_path, j, w, h, o->part, o->parts, rgb, fr, e);
    outdir_unlock(lock);
    if (rc != 0 && made_dir)
        rmdir(dir); /* a part that failed to write leaves no empty folder of ours */
    return rc;
}
