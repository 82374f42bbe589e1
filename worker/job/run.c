/* run: one job from its loaded settings to an image and its sidecar on disk. */
#include "run.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "image/imgio.h"
#include "base/hash.h"
#include "base/sbuf.h"
#include "job_limits.h"
#include "job_path.h"
#include "part.h"
#include "outdir.h"
#include "run_out.h"
#include "scenefile/scene_load.h"
#include "sidecar.h"

struct progress {
    const struct run_opts *o; /* its tick, called at every report */
    const char *name;
    int enabled, last_pct;
};

static void show_progress(void *arg, int done, int rows, double elapsed)
{
    struct progress *p = arg;
    if (p->o->tick)
        p->o->tick(p->o->tick_arg, done, rows, elapsed);
    if (!p->enabled || rows == 0)
        return;
    int pct = (int)(100.0 * done / rows);
    if (pct == p->last_pct && done != rows)
        return;
    p->last_pct = pct;
    char eta[32] = "--"; /* unknown until a row is done */
    if (done > 0)
        snprintf(eta, sizeof eta, "%.1f s", elapsed * (rows - done) / done);
    char name[4 * 128 + 1]; /* the job's name as the terminal sanitiser shows it */
    fprintf(stderr, "\r%s: %3d%% (%d/%d rows) %.1f s elapsed, ETA %s   ",
            sbuf_show(p->name, name, sizeof name), pct, done, rows, elapsed, eta);
    if (done == rows)
        fprintf(stderr, "\n");
}

/* run_load_reference from the reference's bytes already read (data, len), or its file when data is NULL. */
static int decode_reference(const struct job *j, const uint8_t *data, size_t len, int w, int h,
                            struct rgbf *ref, enum img_domain *domain, struct err *e)
{
    const int *at = job_at(j, "reference");
    size_t bad = 0;
    *ref = (struct rgbf){0};
    *domain = IMG_LINEAR;
    if (!j->reference[0])
        return 0;
    if ((data ? imgio_decode_f(data, len, j->reference, ref, domain, e)
              : imgio_read_f(j->reference, ref, domain, e)) < 0) {
        char why[sizeof e->msg];
        snprintf(why, sizeof why, "%s", e->msg);
        return err_set(e, j->path, at[0], at[1], "reference: %s: %s", j->reference, why);
    }
    /* refused before the render, as a compare job's: another size, or NaN or infinite values
       (every error against them would be NaN) */
    if (ref->w != w || ref->h != h)
        err_set(e, j->path, at[0], at[1], "reference: image is %dx%d but the job renders %dx%d", ref->w,
                ref->h, w, h);
    else if ((bad = image_f_nonfinite(ref)))
        err_set(e, j->path, at[0], at[1], "reference: %s: %zu of its %zu values are NaN or infinite",
                j->reference, bad, (size_t)w * h * 3);
    else
        return 0;
    image_f_free(ref);
    return -1;
}

int run_load_reference(const struct job *j, int w, int h, struct rgbf *ref, enum img_domain *domain,
                       struct err *e)
{
    return decode_reference(j, NULL, 0, w, h, ref, domain, e);
}

void run_warn_display_reference(const char *job_name, const char *path)
{
    err_print("%s: warning: reference %s is an 8-bit PNG/PPM: the error is measured on 8-bit display "
              "values (clipped, gamma 2), not on linear radiance; give an EXR or PFM reference\n",
              job_name, path);
}

/* Resume: the outputs (rr->out) exist and were made from these very inputs. */
static int outputs_current(const struct job *j, const struct run_opts *o, const struct run_result *rr)
{
    if (j->hash == 0) /* a job not read from a file (no jobfile_open): nothing to compare with */
        return 0;
    if (o->parts > 0)
        return part_matches(rr->out.image[0], j, o->part, o->parts);
    for (int i = 0; i < rr->out.n_images; i++)
        if (!job_path_is_file(rr->out.image[i]))
            return 0;
    return sidecar_matches(rr->out.sidecar, j->hash);
}

int run_job(const struct job *j, const struct run_opts *o, struct run_result *rr, struct err *e)
{
    /* Outputs of another process count (their sidecar records it) are not what --processes asked
       for: an override joins the hash the outputs are matched by. (Parts keep the file's hash:
       merge matches them against it, whatever split rendered them.) */
    struct job overridden;
    if (j->hash != 0 && o->parts == 0 && o->processes > 0 && o->processes != j->processes) {
        overridden = *j;
        overridden.hash = hash_u64(j->hash, (uint64_t)o->processes);
        j = &overridden;
    }
    struct scene_file sf = {0};
    struct sampler *pix = NULL, *light = NULL;
    struct rgbf ref = {0};
    enum img_domain ref_domain = o->ref_domain;
    float *rgb = NULL;
    int rc = 2;
    memset(rr, 0, sizeof *rr);
    if (o->parts > 0)
        outdir_part_files(j, o->out_dir, o->part, o->parts, &rr->out);
    else
        outdir_files(j, o->out_dir, &rr->out);
    if (!o->force && outputs_current(j, o, rr)) {
        rr->skipped = 1;
        return 0;
    }
    if ((o->scene ? scene_load_src(o->scene, &sf, e) : scene_load(j->scene_path, &sf, e)) < 0)
        goto done;
    snprintf(rr->scene_warning, sizeof rr->scene_warning, "%s", sf.warning);
    int w = j->spec.width;
    int h = job_height(j, sf.aspect);
    if (h > IMAGE_MAX_SIDE) {
        /* only a given width can get here (300 / the smallest aspect, 0.01, is within the limit) */
        err_set(e, j->path, job_at(j, "width")[0], job_at(j, "width")[1],
                "width: %d / the camera's aspect %g gives %d rows (limit %d); give height:", w, sf.aspect, h,
                IMAGE_MAX_SIDE);
        goto done;
    }
    rr->width = w;
    rr->height = h;
    struct camera cam;
    if (camera_init(&cam, &sf.camera, (double)w / h, e) < 0) {
        snprintf(e->file, sizeof e->file, "%s", j->scene_path);
        goto done;
    }
    if (!o->ref && decode_reference(j, o->ref_bytes, o->ref_len, w, h, &ref, &ref_domain, e) < 0)
        goto done;
    if (o->parts == 0 && !o->ref && ref.px && ref_domain == IMG_DISPLAY8)
        run_warn_display_reference(j->name, j->reference);
    const struct rgbf *use_ref = o->ref ? o->ref : &ref;
    if (job_limits_samples(j, w, h, e) < 0)
        goto done;
    if (job_limits_memory("the framebuffer", (size_t)w * h * 3 * sizeof(float) + (size_t)w * h * 3, e) < 0) {
        char why[sizeof e->msg];
        snprintf(why, sizeof why, "%s", e->msg); /* at the size's key: the user's lever */
        const int *at = job_at(j, "width");
        err_set(e, j->path, at[0] ? at[0] : 1, at[0] ? at[1] : 1, "%s: %dx%d pixels: %s",
                at[0] ? "width" : "size", w, h, why);
        goto done;
    }
    if (render_spec_samplers_new(&j->spec, j->spec.seed, &pix, &light, e) < 0) {
        snprintf(e->file, sizeof e->file, "%s", j->path);
        goto done;
    }
    /* Nothing is made before the outputs are written: a failed or stopped render leaves no folder. */
    if (outdir_check(rr->out.dir, e) < 0)
        goto done;
    rc = 1;
    if (!(rgb = procs_framebuffer_new(w, h, e)))
        goto done;
    struct progress prog = {o, o->label ? o->label : j->name, o->progress && !o->quiet, -1};
    struct procs_job fj = {.scene = sf.scene,
                           .camera = &cam,
                           .rs = render_spec_settings(&j->spec, w, h, j->spec.seed),
                           .pixel = pix,
                           .light = light,
                           .processes = o->processes > 0 ? o->processes : j->processes,
                           .row_part = o->parts > 0 ? o->part : 0,
                           .row_parts = o->parts > 0 ? o->parts : 1,
                           .progress = show_progress,
                           .progress_arg = &prog,
                           .stop = o->stop};
    if (procs_render(&fj, rgb, &rr->procs, e) < 0) {
        if (prog.enabled)
            fprintf(stderr, "\n");
        goto done;
    }
    struct run_frame frame = {rgb, w, h, &rr->procs, use_ref, ref_domain, 0};
    if ((o->parts > 0 ? run_out_write_part(j, o, &frame, rr, e) : run_out_write(j, o, &frame, rr, e)) < 0) {
        rc = e->errnum ? 2
                       : 1; /* the output folder cannot be made or written: bad usage, as before a render */
        goto done;
    }
    rc = 0;
done:
    image_f_free(&ref);
    procs_framebuffer_free(rgb, rr->width, rr->height);
    sampler_free(pix);
    sampler_free(light);
    scene_file_free(&sf);
    return rc;
}

void run_say(const struct run_opts *o, const char *fmt, ...)
{
    if (o->quiet || !o->progress)
        return;
    char text[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    size_t n = strlen(text), nl = n > 0 && text[n - 1] == '\n';
    text[n - nl] = 0;
    struct sbuf b = {0}; /* the names it holds as the terminal sanitiser shows them */
    sbuf_shown(&b, text);
    if (b.buf)
        fprintf(stderr, "%s%s", b.buf, nl ? "\n" : "");
    sbuf_free(&b);
}

void run_format_summary(const struct job *j, const struct run_result *rr, char *buf, size_t n)
{
    const struct render_stats *t = &rr->procs.total;
    int len = snprintf(buf, n, "%s: %dx%d %s t=%g (%.0f spp mean), %d process%s, %.2f s -> %s", j->name,
                       rr->width, rr->height, sampler_kind_name(j->spec.pixel.kind), j->spec.pixel.threshold,
                       t->pixels ? (double)t->samples / t->pixels : 0.0, rr->procs.processes,
                       rr->procs.processes == 1 ? "" : "es", rr->procs.wall_s, rr->out.image[0]);
    for (int i = 1; i <= j->n_more && len > 0 && (size_t)len < n; i++) { /* output: [a.png, a.exr] */
        const char *slash = strrchr(rr->out.image[i], '/');
        len += snprintf(buf + len, n - (size_t)len, ", %s", slash ? slash + 1 : rr->out.image[i]);
    }
}

int run_format_warning(const struct job *j, const struct run_result *rr, char *buf, size_t n)
{
    if (!rr->black && !rr->scene_warning[0])
        return 0;
    /* the scene's warning names the light, which the black image's warning only guesses at */
    if (!rr->black)
        snprintf(buf, n, "%s: warning: %s", j->name, rr->scene_warning);
    else
        snprintf(
            buf, n,
            "%s: warning: the image is entirely black (no light reaches the camera? a light emits from its "
            "front face only: a rect's flip:, a disk's toward:)%s%s",
            j->name, rr->scene_warning[0] ? "; " : "", rr->scene_warning);
    return 1;
}

void run_print_summary(const struct job *j, const struct run_result *rr)
{
    char line[4400];
    run_format_summary(j, rr, line, sizeof line);
    err_print("%s\n", line);
    run_print_warnings(j, rr);
}

void run_print_warnings(const struct job *j, const struct run_result *rr)
{
    char line[1024];
    if (run_format_warning(j, rr, line, sizeof line))
        err_print("%s\n", line);
}
