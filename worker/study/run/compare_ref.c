/* compare_ref: render a compare job's references into OUT/.cache/, or reuse the cached ones. */
#include "compare_ref.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/fileio.h"
#include "image/exr.h"
#include "image/imgio.h"
#include "base/hash.h"
#include "base/rng.h"
#include "job/outdir.h"
#include "job/sidecar.h"

/* The cache key of a scene's reference: its scene file's and texture images' bytes (the scene's
   hash, study_scene.hash), every setting that changes the reference's pixels, and the worker
   program's own bytes: a rebuilt renderer may draw other pixels, and its version string does not
   change with every commit. */
static uint64_t reference_key(const struct compare *c, const struct compare_scene *cs)
{
    struct render_spec s = cs->ref_job.spec;
    s.width = cs->width;
    s.height = cs->height;
    uint64_t h = hash_u64(study_inputs_program_hash(c->inputs), cs->input->hash);
    char text[512];
    int n = render_spec_key_text(&s, "", text, sizeof text - 8);
    n += snprintf(text + n, sizeof text - (size_t)n, " halves");
    return hash_bytes(h, text, (size_t)n);
}

/* The seconds a half took to render and its samples per pixel, from its sidecar (0 when unknown). */
static void half_figures(const char *sidecar, double *wall_s, double *spp)
{
    struct sidecar_info info;
    struct err e;
    int ok = sidecar_read(sidecar, &info, &e) == 0;
    *wall_s = ok && isfinite(info.wall_s) ? info.wall_s : 0;
    *spp = ok && isfinite(info.spp_mean) ? info.spp_mean : 0;
}

/* The record beside a cached half (<stem>.key): its cache key and a hash of the EXR's bytes (exr,
   len) as rendered, so a file of another scene or settings put at its name, a PFM or PNG renamed
   .exr, or a damaged one no longer matches and is rendered again. */
static void record_text(const uint8_t *exr, size_t len, uint64_t key, char *buf, size_t n)
{
    snprintf(buf, n, "worker reference half: key %016llx, exr %016llx\n", (unsigned long long)key,
             (unsigned long long)hash_bytes(HASH_FNV_OFFSET, exr, len));
}

/* Whether the cached half of key whose bytes are exr (len) is the one its record names: 1, else 0. */
static int record_ok(const uint8_t *exr, size_t len, const char *record, uint64_t key)
{
    char want[128];
    uint8_t *have = NULL;
    size_t have_len;
    struct err ignored;
    record_text(exr, len, key, want, sizeof want);
    int ok = fileio_read_all(record, 256, &have, &have_len, &ignored) == 0 && have_len == strlen(want) &&
             !memcmp(have, want, have_len);
    free(have);
    return ok;
}

/* The cached half at path (of key, its record beside it) read once into img when it is the one its
   record names and of the scene's size: 1, else 0 (img empty). */
static int half_cached(const struct compare_scene *cs, const char *path, const char *record, uint64_t key,
                       struct rgbf *img)
{
    uint8_t *data = NULL;
    size_t len = 0;
    struct err ignored;
    int ok = fileio_read_all(path, EXR_MAX_BYTES, &data, &len, &ignored) == 0 &&
             record_ok(data, len, record, key) && imgio_decode_f(data, len, path, img, NULL, &ignored) == 0 &&
             img->w == cs->width && img->h == cs->height;
    free(data);
    if (!ok)
        image_f_free(img);
    return ok;
}

/* The half just rendered at path read back once into img, and its record written. 0 or -1. */
static int half_rendered(const char *path, const char *record, uint64_t key, struct rgbf *img, struct err *e)
{
    uint8_t *data = NULL;
    size_t len = 0;
    char text[128];
    int rc = -1;
    if (fileio_read_all(path, EXR_MAX_BYTES, &data, &len, e) == 0 &&
        imgio_decode_f(data, len, path, img, NULL, e) == 0) {
        record_text(data, len, key, text, sizeof text);
        rc = fileio_write_atomic(record, text, strlen(text), e);
    }
    free(data);
    return rc;
}

void compare_ref_half_job(const struct compare_scene *cs, int h, struct job *j)
{
    *j = cs->ref_job;
    j->spec.pixel.threshold = fmin(100, j->spec.pixel.threshold * sqrt(2));
    j->spec.light.threshold = fmin(100, j->spec.light.threshold * sqrt(2));
    j->spec.seed = h ? rng_mix64(j->spec.seed)
                     : j->spec.seed; /* independent of the other half and of the study's seeds */
}

/* Half h's job as rendered into the cache (key: the reference's), its files and its record's path. */
static void half_files(const struct compare_scene *cs, int h, uint64_t key, const struct run_opts *o,
                       struct job *j, struct outdir_files *files, char *record, size_t n)
{
    compare_ref_half_job(cs, h, j);
    snprintf(j->name, sizeof j->name, ".cache");
    j->format = IMG_EXR; /* linear radiance, as every error is measured in */
    j->n_more = 0;       /* one image */
    snprintf(j->output, sizeof j->output, "ref-%s-%016llx-%c.exr", cs->name, (unsigned long long)key,
             "ab"[h]);
    outdir_files(j, o->out_dir, files);
    snprintf(record, n, "%.*s.key", (int)(strlen(files->image[0]) - 4), files->image[0]);
}

/* Half h rendered into the cache, or found there (img its pixels); its time and samples added to
   got->fig, its reused cleared when it was rendered. 0, 1 or 2. */
static int half(const struct compare_scene *cs, int h, uint64_t key, const struct run_opts *o,
                struct rgbf *img, struct study_ref_result *got, struct err *e)
{
    struct job j;
    struct outdir_files files;
    char record[JOB_PATH_MAX + 8];
    half_files(cs, h, key, o, &j, &files, record, sizeof record);
    const char *path = files.image[0], *sidecar = files.sidecar;
    double wall_s = 0, spp = 0;
    if (half_cached(cs, path, record, key, img)) {
        half_figures(sidecar, &wall_s, &spp);
    } else {
        if (access(path, F_OK) == 0)
            run_say(o,
                    "%s: the cached half %s is not the one its record names (damaged, replaced or of an "
                    "older worker): rendering it again\n",
                    cs->name, path);
        got->fig.reused = 0;
        char light[96];
        run_say(o, "%s: rendering the reference's half %c (%s t=%g, %s, seed %llu) into %s\n", cs->name,
                "ab"[h], sampler_kind_name(j.spec.pixel.kind), j.spec.pixel.threshold,
                job_light_text(&j, light, sizeof light), (unsigned long long)j.spec.seed, path);
        struct run_result rr;
        struct run_opts forced = *o;
        forced.force = 1;               /* its sidecar may call a damaged image current */
        forced.scene = &cs->input->src; /* the scene as the study read it */
        char label[JOB_NAME_MAX + 32];
        snprintf(label, sizeof label, "%s reference %c", cs->name, "ab"[h]);
        forced.label = label;
        int rc = run_job(&j, &forced, &rr, e);
        if (rc != 0) {
            err_prefix(e, "reference");
            return rc;
        }
        wall_s = rr.procs.wall_s;
        spp = rr.procs.total.pixels ? (double)rr.procs.total.samples / rr.procs.total.pixels : 0;
        if (half_rendered(path, record, key, img, e) < 0)
            return 1;
    }
    got->fig.wall_s += wall_s;
    got->fig.spp += spp;
    return 0;
}

int compare_ref_half_target(const struct compare *c, int s, int h, const struct run_opts *o, struct job *j)
{
    const struct compare_scene *cs = &c->scenes[s];
    uint64_t key = reference_key(c, cs);
    struct outdir_files files;
    struct rgbf img = {0};
    char record[JOB_PATH_MAX + 8];
    half_files(cs, h, key, o, j, &files, record, sizeof record);
    j->hash = key;
    int cached = half_cached(cs, files.image[0], record, key, &img);
    image_f_free(&img);
    return cached;
}

int compare_ref_half_render(const struct compare *c, int s, int h, const struct run_opts *o, struct err *e)
{
    struct rgbf img = {0};
    struct study_ref_result figures = {0}; /* the reference's are the prepared whole's */
    int rc = half(&c->scenes[s], h, reference_key(c, &c->scenes[s]), o, &img, &figures, e);
    image_f_free(&img);
    return rc;
}

int compare_ref_half_merged(const struct compare *c, int s, int h, const struct run_opts *o, struct err *e)
{
    const struct compare_scene *cs = &c->scenes[s];
    uint64_t key = reference_key(c, cs);
    struct job j;
    struct outdir_files files;
    struct rgbf img = {0};
    char record[JOB_PATH_MAX + 8];
    half_files(cs, h, key, o, &j, &files, record, sizeof record);
    int rc = half_rendered(files.image[0], record, key, &img, e);
    image_f_free(&img);
    return rc;
}

/* The reference = the mean of its halves a and b (into a), and its own noise from their
   difference: each half has variance s2 per value, their mean s2 / 2 and a - b 2 s2, so the mean's
   relMSE is the mean of (a - b)^2 / 4 / (m^2 + 0.01), over the mask's pixels as the variants'.
   Its mean radiance (the mean over the mask's pixels of the channels' mean) has the variance of
   the sum over those P pixels of the channels' mean difference squared / 4, over P^2: pixels are
   independent (per-pixel seeds), a pixel's channels are not (one path carries all three: in a grey
   scene they move together, and counting them apart made the error sqrt(3) too small). */
static void mean_of_halves(struct study_ref_result *rr, const struct img_mask *mask, struct rgbf *a,
                           const struct rgbf *b)
{
    size_t n = (size_t)a->w * a->h, counted = 0;
    double rel = 0, sum = 0, var = 0;
    for (size_t i = 0; i < n; i++) {
        int on = mask_on(mask, (int)(i % (size_t)a->w), (int)(i / (size_t)a->w));
        double pix_d = 0;
        for (int c = 0; c < 3; c++) {
            size_t j = 3 * i + (size_t)c;
            double m = 0.5 * ((double)a->px[j] + b->px[j]), d = (double)a->px[j] - b->px[j];
            if (on)
                rel += d * d / 4 / (m * m + METRICS_REL_EPS), sum += m / 3;
            pix_d += d / 3;
            a->px[j] = (float)m;
        }
        if (on)
            var += pix_d * pix_d / 4, counted++;
    }
    rr->fig.relmse = rel / (double)(3 * counted);
    rr->fig.radiance = sum / (double)counted;
    rr->fig.radiance_se = sqrt(var) / (double)counted;
}

void compare_ref_measure(const struct compare_scene *cs, struct study_ref_result *rr)
{
    rr->fig.relmse = rr->fig.radiance = rr->fig.radiance_se = NAN;
    const char *dot = strrchr(rr->path, '.');
    int stem = dot ? (int)(dot - rr->path) : (int)strlen(rr->path);
    char path[JOB_PATH_MAX + 8];
    struct rgbf a = {0}, b = {0};
    struct err ignored;
    double wall_s, spp;
    rr->fig.spp = 0;
    for (int h = 0; h < 2; h++) {
        snprintf(path, sizeof path, "%.*s-%c.json", stem, rr->path, "ab"[h]);
        half_figures(path, &wall_s, &spp);
        rr->fig.spp += spp;
        snprintf(path, sizeof path, "%.*s-%c.exr", stem, rr->path, "ab"[h]);
        if (imgio_read_f(path, h ? &b : &a, NULL, &ignored) < 0)
            break;
    }
    if (a.px && b.px && a.w == b.w && a.h == b.h)
        mean_of_halves(rr, cs->mask, &a, &b);
    image_f_free(&a), image_f_free(&b);
}

/* The mean m of the halves as rr->path holds it, kept in c->inputs as rr->ref: the file read once
   when the halves were reused and it matches, else written from m. 0 or -1. */
static int keep_mean(const struct compare *c, const struct compare_scene *cs, struct study_ref_result *rr,
                     struct rgbf *m, struct err *e)
{
    struct study_ref r = {.domain = IMG_LINEAR, .fig = rr->fig};
    uint8_t *data = NULL;
    size_t len = 0;
    struct rgbf had = {0};
    struct err ignored;
    int current = rr->fig.reused && fileio_read_all(rr->path, EXR_MAX_BYTES, &data, &len, &ignored) == 0 &&
                  imgio_decode_f(data, len, rr->path, &had, NULL, &ignored) == 0 && had.w == m->w &&
                  had.h == m->h && !memcmp(had.px, m->px, sizeof *m->px * 3 * (size_t)m->w * m->h);
    image_f_free(&had);
    if (!current) {
        free(data);
        data = NULL;
        if (imgio_encode_f(m, IMG_EXR, NULL, 0, &data, &len, e) < 0 ||
            fileio_write_atomic(rr->path, data, len, e) < 0) {
            free(data);
            return -1;
        }
    }
    snprintf(r.path, sizeof r.path, "%s", rr->path);
    r.scene_hash = cs->input->hash;
    r.hash = hash_bytes(r.scene_hash, data, len); /* the bytes as the file holds them */
    free(data);
    r.f = *m; /* taken over */
    *m = (struct rgbf){0};
    if (image_alloc(&r.display, r.f.w, r.f.h, e) < 0) {
        study_ref_free(&r);
        return -1;
    }
    image_float_to_rgb8(r.f.px, r.f.w, r.f.h, r.display.px);
    return (rr->ref = study_inputs_keep_ref(c->inputs, &r, e)) ? 0 : -1;
}

int compare_ref_prepare(const struct compare *c, int s, struct study_results *res, const struct run_opts *o,
                        struct err *e)
{
    const struct compare_scene *cs = &c->scenes[s];
    struct study_ref_result *rr = &res->refs[s];
    rr->fig.relmse = rr->fig.radiance = rr->fig.radiance_se = NAN;
    if (cs->ref_kind == COMPARE_REF_IMAGE) { /* given: read at load */
        rr->ref = cs->image;
        snprintf(rr->path, sizeof rr->path, "%s", cs->image->path);
    }
    if (cs->ref_kind != COMPARE_REF_SETTINGS)
        return 0;
    uint64_t key = reference_key(c, cs);
    struct job j = cs->ref_job;
    snprintf(j.name, sizeof j.name, ".cache");
    snprintf(j.output, sizeof j.output, "ref-%s-%016llx.exr", cs->name, (unsigned long long)key);
    struct outdir_files files;
    outdir_files(&j, o->out_dir, &files);
    snprintf(rr->path, sizeof rr->path, "%s", files.image[0]);
    const struct study_ref *kept = study_inputs_find_ref(c->inputs, rr->path, cs->input->hash);
    if (kept) { /* another study of the suite prepared it: as if reused from the cache */
        rr->ref = kept, rr->fig = kept->fig;
        rr->fig.reused = 1;
    } else {
        rr->fig.reused = 1, rr->fig.wall_s = 0, rr->fig.spp = 0;
        struct rgbf a = {0}, b = {0};
        int rc = half(cs, 0, key, o, &a, rr, e);
        if (rc == 0)
            rc = half(cs, 1, key, o, &b, rr, e);
        if (rc == 0) {
            mean_of_halves(rr, NULL, &a, &b); /* kept for every study: the whole image's */
            rc = keep_mean(c, cs, rr, &a, e) < 0;
        }
        image_f_free(&a), image_f_free(&b);
        if (rc != 0)
            return rc;
    }
    if (cs->mask) /* its noise over the mask, from the halves as written */
        compare_ref_measure(cs, rr);
    if (rr->fig.reused)
        run_say(o, "%s: reference reused from cache %s (it took %.1f s to render)\n", cs->name, rr->path,
                rr->fig.wall_s);
    return 0;
}

void compare_ref_summary(const struct compare *const *cs, int n, int suite, char *refs, size_t refs_n,
                         char *resumed, size_t resumed_n)
{
    int rendered = 0, reused = 0, given = 0, current = 0;
    double saved_s = 0;
    for (int i = 0; i < n; i++) {
        for (int s = 0; s < cs[i]->n_scenes; s++) {
            const struct study_ref_figures *f = &cs[i]->results.refs[s].fig;
            int settings = cs[i]->scenes[s].ref_kind == COMPARE_REF_SETTINGS;
            rendered += settings && !f->reused, reused += settings && f->reused;
            saved_s += settings && f->reused ? f->wall_s : 0;
            given += cs[i]->scenes[s].ref_kind == COMPARE_REF_IMAGE;
        }
        for (int k = 0; k < cs[i]->n_items; k++)
            current += cs[i]->results.rows[k].skipped;
    }
    const char *also = given ? ", images given" : "";
    snprintf(refs, refs_n, "no reference");
    if (reused)
        snprintf(refs, refs_n, "references: %d rendered, %d reused from cache (saving %.1f s)%s", rendered,
                 reused, saved_s, also);
    else if (rendered)
        snprintf(refs, refs_n, "references: %d rendered, 0 reused from cache%s", rendered, also);
    else if (given)
        snprintf(refs, refs_n, "%s", suite ? "reference images given" : "reference image given");
    resumed[0] = 0;
    if (current)
        snprintf(resumed, resumed_n, ", %d of them current from an earlier run (--force renders all)",
                 current);
}
