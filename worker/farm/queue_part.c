/* queue_part: a study's entry rendered whole or as a row part, and a render's parts merged once. */
#include "queue_part.h"

#include <fcntl.h>
#include <stdio.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/hash.h"
#include "job/outdir.h"
#include "job/part.h"
#include "job/sidecar.h"
#include "merge.h"

/* 1 when j's merged image(s) and sidecar are in place and made from j's inputs. */
static int image_current(const struct job *j, const struct run_opts *jo)
{
    struct outdir_files files;
    struct stat st;
    outdir_files(j, jo->out_dir, &files);
    for (int i = 0; i < files.n_images; i++)
        if (lstat(files.image[i], &st) < 0 || !S_ISREG(st.st_mode))
            return 0;
    return sidecar_matches(files.sidecar, j->hash);
}

/* 1 when the render of x (job j) is merged already: its image current, or its half in the cache. */
static int merged(struct study_fan *f, const struct spread_entry *x, const struct job *j,
                  const struct run_opts *jo)
{
    if (x->kind == STUDY_FAN_IMAGE)
        return image_current(j, jo);
    struct job again;
    char dir[2048];
    struct run_opts ao;
    struct err ignored;
    struct study_fan_which w = {.k = x->k, .kind = x->kind, .index = x->index, .half = x->half};
    return study_fan_render_job(f, &w, jo, &again, &ao, dir, sizeof dir, &ignored) == 3;
}

/* Every part of j's render (x->parts of them) whole and rendered from j's inputs: 1, else 0. */
static int all_parts(const struct job *j, const struct run_opts *jo, int parts)
{
    char path[4096];
    for (int i = 0; i < parts; i++) {
        outdir_part_path(j, jo->out_dir, i, parts, path, sizeof path);
        if (!part_matches(path, j, i, parts))
            return 0;
    }
    return 1;
}

/* The render's parts merged when they are all there and it is not merged yet, under a lock beside
   them (two workers that end its last parts at once merge it once). 1 merged now, 0 not (a part
   missing, or merged already), -1 with e filled. */
static int merge_if_last(struct study_fan *f, const struct spread_entry *x, const struct job *j,
                         const struct run_opts *jo, struct err *e)
{
    struct outdir_files files;
    char lock[4200];
    outdir_part_files(j, jo->out_dir, x->part, x->parts, &files);
    snprintf(lock, sizeof lock, "%s/.merge-%s.lock", files.dir, j->output);
    int fd = open(lock, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0)
        return err_set(e, lock, 0, 0, "cannot open the merge lock");
    (void)flock(fd, LOCK_EX); /* released by close, or by its holder's death */
    int rc = 0, done = merged(f, x, j, jo);
    if (!done && all_parts(j, jo, x->parts)) {
        struct run_result rr;
        struct run_opts whole = *jo;
        whole.part = whole.parts = 0;
        rc = merge_parts(j, &whole, &rr, e) != 0 ? -1 : 1;
        if (rc == 1 && x->kind == STUDY_FAN_REFERENCE &&
            study_fan_half_merged(f, x->k, x->index, x->half, jo, e))
            rc = -1;
        done = rc == 1;
    }
    if (done) {
        /* merged: its parts are spent (a worker that renders one again finds it merged, under this
           lock) and the output folder holds what a one-process run writes; the lock goes too (whoever
           opens it anew checks the merge first) */
        char path[4096];
        for (int i = 0; i < x->parts; i++) {
            outdir_part_path(j, jo->out_dir, i, x->parts, path, sizeof path);
            unlink(path);
        }
        unlink(lock);
    }
    close(fd);
    return rc;
}

int queue_part_render(struct study_fan *f, const struct spread_entry *x, const struct run_opts *o, char *msg,
                      size_t n, struct err *e)
{
    const struct compare *c = x->k >= 0 && x->k < study_fan_studies(f) ? study_fan_study(f, x->k) : NULL;
    char what[600], dir[2048];
    if (c && x->kind == STUDY_FAN_REFERENCE && x->index >= 0 && x->index < c->n_scenes)
        snprintf(what, sizeof what, "%s: reference of %s, half %c", c->name, c->scenes[x->index].name,
                 "ab"[x->half]);
    else if (c && x->kind == STUDY_FAN_IMAGE && x->index >= 0 && x->index < c->n_items)
        snprintf(what, sizeof what, "%s: image %d of %d (%s)", c->name, x->index + 1, c->n_items,
                 c->items[x->index].job.output);
    else
        snprintf(what, sizeof what, "no such render");
    struct job j;
    struct run_opts jo;
    struct study_fan_which w = {.k = x->k, .kind = x->kind, .index = x->index, .half = x->half};
    if (x->kind == STUDY_FAN_REFERENCE && study_fan_render_job(f, &w, o, &j, &jo, dir, sizeof dir, e) == 3) {
        snprintf(msg, n, "%s: in the cache already, not rendered", what);
        return 0;
    }
    e->msg[0] = 0;
    if (x->parts == 1) {
        int rc = x->kind == STUDY_FAN_REFERENCE ? study_fan_render_half(f, x->k, x->index, x->half, o, e)
                                                : study_fan_render(f, x->k, x->kind, x->index, o, e);
        if (rc == 0)
            snprintf(msg, n, "%s: %s", what,
                     x->kind == STUDY_FAN_IMAGE && c->results.rows[x->index].skipped
                         ? "current, not rendered again"
                         : "rendered");
        return rc;
    }
    int rc = study_fan_render_job(f, &w, o, &j, &jo, dir, sizeof dir, e);
    /* the hash run_job gives a whole render under --processes (run.h): the merged sidecar records
       it, so the gather (the whole job, with the same option) finds the image current */
    if (rc == 0 && x->kind == STUDY_FAN_IMAGE && j.hash != 0 && o->processes > 0 &&
        o->processes != j.processes)
        j.hash = hash_u64(j.hash, (uint64_t)o->processes);
    if (rc == 3 || (rc == 0 && x->kind == STUDY_FAN_IMAGE && image_current(&j, &jo))) {
        snprintf(msg, n, "%s, part %d/%d: merged already (current), not rendered", what, x->part + 1,
                 x->parts);
        return 0;
    }
    if (rc != 0)
        return rc;
    struct run_opts po = jo;
    struct run_result rr;
    po.part = x->part;
    po.parts = x->parts;
    po.force = 0;  /* a part current from a killed worker's render is not rendered again */
    po.ref = NULL; /* a part is scored once merged */
    po.ref_display = NULL;
    po.progress = 0;
    if ((rc = run_job(&j, &po, &rr, e)) != 0) {
        err_prefix(e, what);
        return rc;
    }
    int m = merge_if_last(f, x, &j, &jo, e);
    if (m < 0) {
        err_prefix(e, what);
        return 1;
    }
    snprintf(msg, n, "%s, part %d/%d: %s%s", what, x->part + 1, x->parts,
             rr.skipped ? "current, not rendered again" : "rendered",
             m ? "; every part there: merged into its image and sidecar" : "");
    return 0;
}
