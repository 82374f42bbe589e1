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

/* The EXR header's string attributes for j (nothing that depends on the process count or the
   output folder: the file's bytes do not). texts holds their values. */
static size_t exr_attrs(const struct job *j, struct img_attr *a, char texts[][160])
{
    const char *slash = strrchr(j->scene_path, '/');
    snprintf(texts[0], 160, "%s", slash ? slash + 1 : j->scene_path);
    snprintf(texts[1], 160, "%s t=%.17g", sampler_kind_name(j->spec.pixel.kind), j->spec.pixel.threshold);
    snprintf(texts[2], 160, "%s t=%.17g", sampler_kind_name(j->spec.light.kind), j->spec.light.threshold);
    snprintf(texts[3], 160, "%llu", (unsigned long long)j->spec.seed);
    snprintf(texts[4], 160, "%d", j->spec.max_depth);
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

/* Encode image i of rr->out from the framebuffer fb (or its 8-bit conversion img) and stage it
   under a temporary name into staged. 0 or -1 with e filled. */
static int stage_image(const struct job *j, const struct run_result *rr, int i, const struct rgbf *fb,
                       const struct rgb8 *img, char *staged, size_t n, struct err *e)
{
    char attr_text[6][160];
    struct img_attr attrs[8];
    uint8_t *buf = NULL;
    size_t len = 0;
    enum img_format fmt = rr->out.format[i];
    int rc = imgio_is_float(fmt)
                 ? imgio_encode_f(fb, fmt, attrs, exr_attrs(j, attrs, attr_text), &buf, &len, e)
                 : imgio_encode(img, fmt, &buf, &len, e);
    if (rc == 0)
        rc = fileio_stage(rr->out.image[i], buf, len, staged, n, e);
    else if (!e->file[0])
        snprintf(e->file, sizeof e->file, "%s", rr->out.image[i]);
    free(buf);
    return rc;
}

/* Remove the earlier sidecar (final[n - 1]), then rename the n staged files to their final names,
   in order (the sidecar last), asking before each whether the claim is still held. 0, or -1 with
   e filled and nothing of this writer's left (an image without its sidecar is no finished job). */
static int commit_all(const struct run_opts *o, const char *dir, char staged[][2100],
                      const char *const *final, int n, struct err *e)
{
    for (int i = 0; i < n; i++) {
        /* a writer stopped (SIGSTOP) until its claim was taken over renames nothing, lock or not; a
           claim taken over between renames: what is renamed stays, without a sidecar */
        int failed = o->still_held && !o->still_held(o->tick_arg);
        if (failed)
            err_set(e, NULL, 0, 0, "the claim was taken over while it wrote %s/: nothing written", dir);
        else if (i == 0 && unlink(final[n - 1]) < 0 && errno != ENOENT)
            failed = err_set_errno(e, errno, "cannot write %s: %s", final[n - 1], strerror(errno)) < 0;
        if (failed) {
            for (int r = i; r < n; r++)
                unlink(staged[r]);
            return -1;
        }
        if (fileio_commit(staged[i], final[i], e) == 0)
            continue;
        for (int r = 0; r < n; r++)
            if (r != i)
                unlink(r < i ? final[r] : staged[r]);
        return -1;
    }
    return 0;
}

int run_out_write(const struct job *j, const struct run_opts *o, const struct run_frame *f,
                  struct run_result *rr, struct err *e)
{
    const struct outdir_files *out = &rr->out;
    char staged[OUTDIR_IMAGES_MAX + 1][2100];
    const char *final[OUTDIR_IMAGES_MAX + 2];
    struct rgb8 img = {0};
    struct rgbf fb = {f->w, f->h, (float *)f->rgb};
    char *json = NULL;
    int rc = -1, made_dir = 0, lock = -1, n = 0, k = 0,
        need8 = f->ref && f->ref->px && f->ref_domain == IMG_DISPLAY8;
    for (int i = 0; i < out->n_images; i++) {
        final[n++] = out->image[i];
        need8 |= !imgio_is_float(out->format[i]);
    }
    final[n++] = out->sidecar;
    final[n] = NULL;
    if (outdir_mkdirs(out->dir, &made_dir, e) < 0 || (need8 && image_alloc(&img, f->w, f->h, e) < 0))
        goto done;
    if (run_out_lock_outputs(out->dir, final, o, &lock, e) < 0)
        goto done;
    if (img.px)
        image_float_to_rgb8(f->rgb, f->w, f->h, img.px);
    rr->has_error = rr->has_display_error = 0;
    if (f->ref && f->ref->px && score(&fb, &img, f->ref, f->ref_domain, rr, e) < 0)
        goto done;
    if (o->ref_display && img.px) {
        if (metrics_display_compare(o->ref_display, &img, &rr->display_error, e) < 0)
            goto done;
        rr->has_display_error = 1;
    }
    struct sidecar sc = {j,         f->w,    f->h, f->procs, rr->has_error ? &rr->error : NULL, f->ref_domain,
                         j->output, f->parts};
    if (!(json = sidecar_json(&sc))) {
        err_set(e, NULL, 0, 0, "out of memory writing the sidecar");
        goto done;
    }
    /* All staged whole first: a failure before the renames (a full disk) leaves the earlier outputs
       as they were; then commit_all: a reader (or a writer killed at any step) sees the earlier
       outputs, images without a sidecar (rendered again), or the new ones, never a new image
       beside an earlier sidecar (issue 21, defect 6). */
    for (k = 0; k < n - 1; k++)
        if (stage_image(j, rr, k, &fb, &img, staged[k], sizeof staged[k], e) < 0)
            break;
    if (k < n - 1 || fileio_stage(out->sidecar, json, strlen(json), staged[k], sizeof staged[k], e) < 0) {
        while (k-- > 0)
            unlink(staged[k]);
        goto done;
    }
    if (commit_all(o, out->dir, staged, final, n, e) < 0)
        goto done;
    rr->black = image_float_black(f->rgb, f->w, f->h);
    rc = 0;
done:
    outdir_unlock(lock);
    if (rc != 0 && made_dir)
        rmdir(out->dir); /* a failed write leaves no empty folder of ours (it fails when not empty) */
    free(json);
    image_free(&img);
    return rc;
}

int run_out_write_part(const struct job *j, const struct run_opts *o, const struct run_frame *f,
                       struct run_result *rr, struct err *e)
{
    int made_dir = 0, lock = -1, rc = -1;
    const char *outs[] = {rr->out.image[0], NULL};
    const struct part_frame fb = {f->w, f->h, f->rgb};
    if (outdir_mkdirs(rr->out.dir, &made_dir, e) == 0 &&
        run_out_lock_outputs(rr->out.dir, outs, o, &lock, e) == 0)
        rc = part_write(rr->out.image[0], j, &fb, o->part, o->parts, f->procs, e);
    outdir_unlock(lock);
    if (rc != 0 && made_dir)
        rmdir(rr->out.dir); /* a part that failed to write leaves no empty folder of ours */
    return rc;
}
