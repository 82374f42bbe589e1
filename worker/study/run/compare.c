/* compare: running a loaded compare job: references (cached), every combination, then
   summary.csv, chart.svg and report.html. */
#include "compare.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "compare_cost.h"
#include "compare_ref.h"
#include "study/present/report_chart.h"
#include "base/clock.h"
#include "base/fileio.h"
#include "image/errspec.h"
#include "image/flip.h"
#include "image/imgio.h"
#include "base/hash.h"
#include "job/outdir.h"
#include "job/sidecar.h"
#include "study/present/report.h"
#include "study_machines.h"
#include "study/judge/verdict_from.h"
#include "study/present/verdict_out.h"
#include "job/run_out.h"
#include "base/sbuf.h"

/* What one render is expected to cost, for the ETA: pixels x expected samples per pixel. */
static double cost(const struct compare *c, const struct compare_item *it)
{
    double spp = sampler_expected_spp(it->job.spec.pixel.kind, it->job.spec.pixel.threshold);
    return (double)c->scenes[it->scene].width * c->scenes[it->scene].height * (spp > 1 ? spp : 1);
}

/* The cost design's CPU seconds: every (scene, variant, point) timed once per block. */
static double timing_s(const struct compare *c)
{
    return (double)c->n_scenes * c->n_variants * c->n_points * COMPARE_COST_BLOCKS * COMPARE_COST_UNIT_S;
}

static void fmt_duration(double s, char *buf, size_t n)
{
    if (s < 60)
        snprintf(buf, n, "%.0f s", s);
    else if (s < 3600)
        snprintf(buf, n, "%dm%02ds", (int)s / 60, (int)s % 60);
    else
        snprintf(buf, n, "%dh%02dm", (int)s / 3600, (int)s % 3600 / 60);
}

/* The resume hash of one combination: its scene file's and texture images' bytes, then its reference
   image's bytes (both as the study read them: ref->hash, else cs->input->hash; a cached
   reference's bytes follow its settings, and a reference given as a file may be replaced under the
   same path), every setting that changes its pixels, not its path: the same --out spelled another
   way finds the same outputs current. An image whose sidecar records it is current and is not
   rendered again (unless --force). */
static uint64_t item_hash(const struct compare_scene *cs, const struct study_ref *ref, const struct job *j)
{
    char text[512];
    int n = render_spec_key_text(&j->spec, j->reference[0] ? " ref 1" : " ref 0", text, sizeof text);
    return hash_bytes(j->reference[0] ? ref->hash : cs->input->hash, text, (size_t)n);
}

/* Item i's job as rendered: the plan's, with its scene's prepared reference (r->refs) and the resume
   hash set. 0, or 1 with e filled when the reference was not prepared. */
static int item_job(const struct compare *c, const struct study_results *r, int i, struct job *j,
                    struct err *e)
{
    const struct compare_item *it = &c->items[i];
    const struct compare_scene *cs = &c->scenes[it->scene];
    const struct study_ref_result *rr = &r->refs[it->scene];
    if (cs->ref_kind != COMPARE_REF_NONE && !rr->ref) {
        err_set(e, NULL, 0, 0, "%s: the reference of %s was not prepared", it->job.output, cs->name);
        return 1;
    }
    *j = it->job;
    snprintf(j->reference, sizeof j->reference, "%s", cs->ref_kind != COMPARE_REF_NONE ? rr->path : "");
    j->hash = item_hash(cs, rr->ref, j);
    return 0;
}

/* A combination skipped as current: what it measured, from its sidecar. */
static int item_from_sidecar(struct study_result *r, const char *sidecar_path, struct err *e)
{
    struct sidecar_info info;
    if (sidecar_read(sidecar_path, &info, e) < 0)
        return -1;
    r->spp_mean = info.spp_mean;
    r->wall_s = info.wall_s;
    r->cpu_s = info.cpu_s;
    r->sampler_share = info.sampling_share;
    r->nonfinite = info.nonfinite;
    r->work = info.work;
    return 0;
}

/* The file a combination is scored and looked at in: its float copy, or its PNG for an 8-bit
   reference. */
static const char *scored_file(const struct outdir_files *out, enum img_domain domain)
{
    return out->image[domain == IMG_LINEAR && out->float_copy >= 0 ? out->float_copy : 0];
}

/* How a combination's error looks (errspec.h) and its mean FLIP (HDR-FLIP on linear images,
   LDR-FLIP on 8-bit ones), of img, over the scene's mask (the spectrum: on the mask's bounding
   rectangle, its uncounted pixels given no error). 0 or -1. */
static int score_look_img(struct study_result *r, const struct rgbf *img, const struct study_ref *ref,
                          const struct compare_scene *cs, struct err *e)
{
    struct rgbf cut[2] = {{0}, {0}};
    struct flip_result flip = {0};
    const struct img_mask *m = cs->mask;
    int rc = (m ? mask_crop_pair(m, &ref->f, img, &cut[0], &cut[1], e) < 0 ||
                      errspec_lowfreq(&cut[0], &cut[1], &r->error_lowfreq, e) < 0
                : errspec_lowfreq(&ref->f, img, &r->error_lowfreq, e) < 0) ||
                     (cs->ref_domain == IMG_LINEAR ? flip_hdr : flip_ldr)(&ref->f, img, m, NULL, &flip, e) < 0
                 ? -1
                 : 0;
    r->flip = rc == 0 ? flip.mean : NAN;
    image_f_free(&cut[0]), image_f_free(&cut[1]);
    return rc;
}

/* Score a combination's files (scored_file, read once): how its error looks and its FLIP, measured
   on the file as written; when whole (a combination that was current, or a scene with a mask), its
   error too and its PNG's display figures, over the scene's mask. 0 or -1. */
static int score_files(struct study_result *r, const struct run_result *rr, const struct study_ref *ref,
                       const struct compare_scene *cs, int whole, struct err *e)
{
    struct rgbf img = {0};
    struct rgb8 png = {0};
    const struct outdir_files *out = &rr->out;
    int rc =
        imgio_read_f(scored_file(out, cs->ref_domain), &img, NULL, e) < 0 ||
                (whole && metrics_compare_masked(&ref->f, &img, 1, cs->mask, &r->error, e) < 0) ||
                score_look_img(r, &img, ref, cs, e) < 0 ||
                (whole && (imgio_read(out->image[0], &png, e) < 0 ||
                           metrics_display_masked(&ref->display, &png, cs->mask, &r->display_error, e) < 0))
            ? -1
            : 0;
    image_f_free(&img);
    image_free(&png);
    return rc;
}

/* Render combination i (item_job) or take it as it is when current, and measure it against its
   scene's prepared reference (none when the study has none) into its row of res. */
static int render_item(const struct compare *c, struct study_results *res, int i, const struct run_opts *o,
                       struct err *e)
{
    const struct compare_item *it = &c->items[i];
    const struct compare_scene *cs = &c->scenes[it->scene];
    const struct study_ref *ref = cs->ref_kind != COMPARE_REF_NONE ? res->refs[it->scene].ref : NULL;
    struct study_result *r = &res->rows[i];
    struct job j;
    if (item_job(c, res, i, &j, e) != 0)
        return 1;
    r->hash = j.hash;
    struct run_result rr;
    struct run_opts quiet_rows = *o; /* the combination's own line replaces row progress */
    quiet_rows.progress = 0;
    quiet_rows.scene = &cs->input->src;    /* the scene as the study read it */
    quiet_rows.ref = ref ? &ref->f : NULL; /* scored in memory, on the framebuffer's floats */
    quiet_rows.ref_domain = cs->ref_domain;
    quiet_rows.ref_display = ref ? &ref->display : NULL;
    int rc = run_job(&j, &quiet_rows, &rr, e);
    if (rc != 0) {
        err_prefix(e, it->job.output);
        return rc;
    }
    r->skipped = rr.skipped;
    if (rr.skipped) {
        if (item_from_sidecar(r, rr.out.sidecar, e) < 0)
            return 1;
    } else {
        const struct render_stats *t = &rr.procs.total;
        r->spp_mean = t->pixels ? (double)t->samples / t->pixels : 0;
        r->nonfinite = t->nonfinite;
        r->wall_s = rr.procs.wall_s;
        r->cpu_s = rr.procs.cpu_s;
        r->sampler_share = procs_sampling_share(&rr.procs); /* the sidecar's sampling_share */
        r->work = sidecar_work_of(t);
    }
    int whole = rr.skipped || cs->mask != NULL; /* the sidecar's figures are the whole image's */
    if (ref && !whole) {                        /* the framebuffer's, scored in memory */
        if (!rr.has_error || !rr.has_display_error) {
            err_set(e, NULL, 0, 0, "%s: rendered without its error figures", it->job.output);
            return 1;
        }
        r->error = rr.error;
        r->display_error = rr.display_error;
    }
    if (ref && score_files(r, &rr, ref, cs, whole, e) < 0)
        return 1;
    r->has_error |= ref != NULL;
    r->done = 1;
    return 0;
}

/* One CSV field (sbuf_csv: quoted when it holds a comma, a quote or a line break, as a scene file's
   name may), then `after`. */
static void csv_field(struct sbuf *b, const char *text, const char *after)
{
    sbuf_csv(b, text);
    sbuf_printf(b, "%s", after);
}

static char *summary_csv(const struct compare *c)
{
    struct sbuf b = {0};
    sbuf_printf(&b, "scene,variant,");
    render_spec_csv(NULL, 1, &b); /* the render's settings, a column per render_spec row */
    sbuf_printf(&b,
                "samples_per_pixel_mean,wall_s,cpu_s,"
                "sampler_share,mse,rmse,relmse,relmse_robust,psnr,domain,rmse_8bit,relmse_8bit,error_lowfreq,"
                "flip,camera_samples,path_segments,shadow_rays,pixel_points,light_points,padded_points,"
                "pixel_sets,light_sets,padded_sets,");
    render_spec_csv(NULL, 0, &b);
    sbuf_printf(&b, "image\n");
    for (int i = 0; i < c->n_items; i++) {
        const struct compare_item *it = &c->items[i];
        const struct study_result *r = &c->results.rows[i];
        csv_field(&b, c->scenes[it->scene].name, ",");
        csv_field(&b, c->variants[it->variant], ",");
        struct render_spec spec = it->job.spec; /* at the size rendered */
        spec.width = c->scenes[it->scene].width;
        spec.height = c->scenes[it->scene].height;
        render_spec_csv(&spec, 1, &b);
        sbuf_printf(&b, "%.2f,%.6g,%.6g,%.6g,", r->spp_mean, r->wall_s, r->cpu_s, r->sampler_share);
        if (r->has_error)
            sbuf_printf(&b, "%.6g,%.6g,%.6g,%.6g,%.4f,%s,%.6g,%.6g,", r->error.mse, r->error.rmse,
                        r->error.relmse, r->error.relmse_robust, r->error.psnr,
                        image_domain_name(c->scenes[it->scene].ref_domain), r->display_error.rmse,
                        r->display_error.relmse);
        else
            sbuf_printf(&b, ",,,,,,,,");
        if (r->has_error && isfinite(r->error_lowfreq))
            sbuf_printf(&b, "%.4f,", r->error_lowfreq);
        else
            sbuf_printf(&b, ",");
        sbuf_printf(&b, r->has_error && isfinite(r->flip) ? "%.6g," : ",", r->flip);
        const struct sidecar_work *w = &r->work; /* deterministic: the same on every machine */
        sbuf_printf(&b, "%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,",
                    (unsigned long long)w->camera_samples, (unsigned long long)w->path_segments,
                    (unsigned long long)w->shadow_rays, (unsigned long long)w->pixel_points,
                    (unsigned long long)w->light_points, (unsigned long long)w->padded_points,
                    (unsigned long long)w->pixel_sets, (unsigned long long)w->light_sets,
                    (unsigned long long)w->padded_sets);
        render_spec_csv(&spec, 0, &b);
        csv_field(&b, it->job.output, "\n");
    }
    return sbuf_take(&b);
}

int compare_item_job(const struct compare *c, struct study_results *r, int i, const struct run_opts *o,
                     struct job *j, struct err *e)
{
    int rc = compare_ref_prepare(c, c->items[i].scene, r, o, e);
    return rc != 0 ? rc : item_job(c, r, i, j, e); /* as render_item renders it: the merged sidecar current */
}

int compare_run_item(const struct compare *c, struct study_results *r, int i, const struct run_opts *o,
                     struct err *e)
{
    int rc = compare_ref_prepare(c, c->items[i].scene, r, o, e);
    return rc != 0 ? rc : render_item(c, r, i, o, e);
}

int compare_write_outputs(struct compare *c, const char *dir, const struct run_opts *o, struct err *e)
{
    e->msg[0] = 0;
    /* Written under the folder's lock, as the images are: writers take turns, and the temporaries
       of a writer killed half-way (.summary.csv.tmp.XXXXXX, ...) are removed, never a live one's. */
    char summary[2100], chart[2100], report[2100], verdict[2100], cost_csv[2100];
    snprintf(summary, sizeof summary, "%s/summary.csv", dir);
    snprintf(cost_csv, sizeof cost_csv, "%s/cost.csv", dir);
    snprintf(chart, sizeof chart, "%s/chart.svg", dir);
    snprintf(report, sizeof report, "%s/report.html", dir);
    snprintf(verdict, sizeof verdict, "%s/verdict.json", dir);
    const char *outs[] = {summary, chart, report, verdict, cost_csv, NULL};
    int lock = -1, rc = -1;
    verdict_study_free(&c->verdict);
    study_env_read(&c->env);
    struct verdict_found found;
    study_machines_read(c, o->out_dir, &found);
    if ((c->has_verdict = verdict_from_compare(c, dir, &found, &c->verdict, e) == 0) == 0)
        return -1;
    verdict_print_warnings(&c->verdict, 1);
    if (outdir_mkdirs(dir, NULL, e) == 0 && run_out_lock_outputs(dir, outs, o, &lock, e) == 0 &&
        fileio_write_text(dir, "summary.csv", summary_csv(c), e) == 0 &&
        (c->results.n_blocks == 0 || fileio_write_text(dir, "cost.csv", compare_cost_csv(c), e) == 0) &&
        fileio_write_text(dir, "chart.svg", report_chart_svg(c), e) == 0 &&
        fileio_write_text(dir, "verdict.json", verdict_json_text(c->name, &c->verdict, 1, &c->env), e) == 0 &&
        fileio_write_text(dir, "report.html", report_html(c, dir, e), e) == 0)
        rc = 0;
    outdir_unlock(lock);
    return rc;
}

/* The study's costs: timed now (compare_cost.h), unless every image was current and the folder's
   cost.csv covers them (a resumed study keeps its figures). 0, or 1 with e filled. */
static int study_costs(const struct compare *c, struct study_results *r, const char *dir,
                       const struct run_opts *o, struct err *e)
{
    int current = 1;
    for (int i = 0; i < c->n_items; i++)
        current &= r->rows[i].skipped;
    if (current && compare_cost_read(c, r, dir) == 0)
        return 0;
    run_say(o, "timing: %d blocks of every variant and point, about %.0f s of CPU\n", COMPARE_COST_BLOCKS,
            timing_s(c));
    return compare_cost_measure(c, r, o, e) < 0;
}

int compare_run(struct compare *c, const struct run_opts *o, struct err *e)
{
    char dir[2048];
    int rc = 1;
    double t0 = clock_s(CLOCK_MONOTONIC), total = 0, done = 0;
    outdir_dir(o->out_dir, c->name, dir, sizeof dir);
    /* Checked now, made only when the first image or the summary is written: a job stopped or
       failed before that (a reference render cut short by Ctrl-C) leaves no empty folder. */
    if (outdir_check(dir, e) < 0)
        return 2;
    for (int s = 0; s < c->n_scenes; s++) {
        if ((rc = compare_ref_prepare(c, s, &c->results, o, e)) != 0)
            return rc;
        const struct compare_scene *cs = &c->scenes[s];
        if (cs->ref_kind != COMPARE_REF_NONE && cs->ref_domain != IMG_LINEAR)
            run_warn_display_reference(c->name, c->results.refs[s].path);
    }
    int *order = malloc(sizeof *order * (size_t)(c->n_items + 1));
    if (!order) {
        err_set(e, NULL, 0, 0, "out of memory");
        return 1;
    }
    compare_cost_order(c, order);
    for (int i = 0; i < c->n_items; i++)
        total += cost(c, &c->items[i]);
    double t1 = clock_s(CLOCK_MONOTONIC);
    for (int n = 0; n < c->n_items; n++) {
        const struct compare_item *it = &c->items[order[n]];
        const struct study_result *r = &c->results.rows[order[n]];
        const struct compare_scene *cs = &c->scenes[it->scene];
        if ((rc = render_item(c, &c->results, order[n], o, e)) != 0) {
            free(order);
            return rc;
        }
        if (r->skipped) /* current from an earlier run: no time spent, none to predict */
            total -= cost(c, it);
        else
            done += cost(c, it);
        double elapsed = clock_s(CLOCK_MONOTONIC) - t1;
        char el[32], eta[32], err_text[48] = "";
        fmt_duration(clock_s(CLOCK_MONOTONIC) - t0, el, sizeof el);
        /* the images still to render, then the cost design's blocks */
        fmt_duration((done > 0 ? elapsed * (total - done) / done : 0) + timing_s(c), eta, sizeof eta);
        if (r->has_error)
            snprintf(err_text, sizeof err_text, ", relMSE %.4g", r->error.relmse);
        run_say(o, "[%*d/%d] %s %s t=%g seed %llu: %.0f spp, %.2f s%s%s | %s elapsed, ETA %s\n",
                c->n_items >= 100 ? 3 : 2, n + 1, c->n_items, cs->name, c->variants[it->variant],
                it->job.spec.pixel.threshold, (unsigned long long)it->job.spec.seed, r->spp_mean, r->wall_s,
                err_text, r->skipped ? " (current, not rendered again)" : "", el, eta);
    }
    free(order);
    if ((rc = study_costs(c, &c->results, dir, o, e)) != 0)
        return rc;
    return compare_write_outputs(c, dir, o, e) < 0;
}

void compare_summary_line(const struct compare *c, double wall_s, const char *out_dir, char *buf, size_t n)
{
    char refs[160], resumed[96], winners[1024] = "";
    compare_ref_summary(&c, 1, 0, refs, sizeof refs, resumed, sizeof resumed);
    if (c->has_verdict)
        verdict_summary(&c->verdict, 1, winners, sizeof winners);
    snprintf(buf, n,
             "%s: %d image%s (%d scene%s x %d variant%s x %d sweep point%s x %d seed%s)%s, %s, %.2f s -> "
             "%s/%s/%s%s",
             c->name, c->n_items, sbuf_plural(c->n_items), c->n_scenes, sbuf_plural(c->n_scenes),
             c->n_variants, sbuf_plural(c->n_variants), c->n_points, sbuf_plural(c->n_points), c->n_seeds,
             sbuf_plural(c->n_seeds), resumed, refs, wall_s, outdir_root(out_dir), c->name,
             winners[0] ? "; at equal CPU time: " : "", winners);
}
