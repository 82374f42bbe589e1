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

int run_out_write(const struct job *j, const struct run_opts *o, const float *rgb, int w, int h,
                  const struct procs_result *fr, const struct rgb8 *ref, int parts, struct run_result *rr,
                  struct err *e)
{
    char dir[2048], staged_image[2100], staged_sidecar[2100];
    struct rgb8 img = {0};
    char *json = NULL;
    int rc = -1, made_dir = 0, lock = -1;
    outdir_paths(j, o->out_dir, dir, rr->image_path, rr->sidecar_path, sizeof rr->image_path);
    if (outdir_mkdirs(dir, &made_dir, e) < 0 || image_alloc(&img, w, h, e) < 0)
        goto done;
    outdir_staged_name(rr->image_path, staged_image, sizeof staged_image);
    outdir_staged_name(rr->sidecar_path, staged_sidecar, sizeof staged_sidecar);
    const char *outs[] = {rr->image_path, rr->sidecar_path, NULL};
    if (run_out_lock_outputs(dir, outs, o, &lock, e) < 0)
        goto done;
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
    /* Both are written whole under staging names first: a failure before the renames (a full disk,
       a size limit) leaves an earlier image and sidecar as they were. Then the earlier sidecar
       goes, the image is renamed, the sidecar last: a reader (or a writer killed at any step)
       sees the earlier pair, an image without a sidecar (not finished: rendered again), or the
       new pair, never a new image beside an earlier sidecar (issue 21, defect 6). A killed
       writer's staged files and their temporaries go under the next one's lock. */
    if (imgio_write(staged_image, &img, j->format, e) < 0) {
        name_final(e, staged_image, rr->image_path);
        goto done;
    }
    if (fileio_write_atomic(staged_sidecar, json, strlen(json), e) < 0) {
        name_final(e, staged_sidecar, rr->sidecar_path);
        unlink(staged_image);
        goto done;
    }
    /* a writer stopped (SIGSTOP) until its claim was taken over renames nothing, lock or not */
    if (run_out_still_held(o, dir, e) < 0) {
        unlink(staged_image);
        unlink(staged_sidecar);
        goto done;
    }
    if ((unlink(rr->sidecar_path) < 0 && errno != ENOENT) || rename(staged_image, rr->image_path) < 0) {
        err_set(e, NULL, 0, 0, "cannot write %s: %s", rr->image_path, strerror(errno));
        unlink(staged_image);
        unlink(staged_sidecar);
        goto done;
    }
    if (run_out_still_held(o, dir, e) < 0) { /* the image stays, without a sidecar: not finished */
        unlink(staged_sidecar);
        goto done;
    }
    if (rename(staged_sidecar, rr->sidecar_path) < 0) {
        err_set(e, NULL, 0, 0, "cannot write %s: %s", rr->sidecar_path, strerror(errno));
        unlink(staged_sidecar);
        unlink(rr->image_path); /* an image without its sidecar is not a finished job */
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
