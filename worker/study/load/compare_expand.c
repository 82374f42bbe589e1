/* compare_expand: a compare job's reference and its combinations as ordinary jobs, with
   clear, stable image names. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare_model.h"
#include "compare_expand.h"
#include "compare_keys.h"
#include "compare_spp.h"
#include "base/fileio.h"
#include "image/exr.h"
#include "job/job_limits.h"

/* reference: settings rendered once per scene, an image path (one scene), or absent. */
int compare_expand_reference(struct compare_loading *L)
{
    struct ydoc *d = &L->d;
    struct compare *c = L->c;
    yaml_node_t *r = L->reference, *k, *v;
    if (!r)
        return 0;
    if (yscalar(r)) {
        if (c->n_scenes > 1)
            return ydoc_fail(d, r, L->e,
                             "reference: an image serves one scene; with %d scenes give settings, "
                             "e.g. reference: { sampler: %s, threshold: 0.5 }",
                             c->n_scenes, sampler_kind_name(SAMPLER_JITTER));
        struct job tmp = L->scene_base[0];
        struct compare_scene *cs = &c->scenes[0];
        if (compare_keys_apply(&tmp, d, "reference", r, L->e) < 0)
            return -1;
        if (!(cs->image = study_inputs_find_ref(c->inputs, tmp.reference, cs->input->hash))) {
            struct study_ref got = {0};
            uint8_t *data = NULL;
            size_t len = 0;
            int rc = fileio_read_all(tmp.reference, EXR_MAX_BYTES, &data, &len, L->e) < 0 ||
                             study_ref_decode(&got, tmp.reference, cs->input->hash, data, len, L->e) < 0
                         ? -1
                         : 0;
            free(data);
            if (rc < 0)
                return ydoc_fail(d, r, L->e, "reference: %s: %s", tmp.reference, L->e->msg);
            if (!(cs->image = study_inputs_keep_ref(c->inputs, &got, L->e)))
                return -1;
        }
        cs->ref_domain = cs->image->domain;
        int w = cs->image->f.w, h = cs->image->f.h;
        size_t bad = image_f_nonfinite(&cs->image->f), n = (size_t)w * h * 3;
        if (bad) /* every error against it would be NaN: found now, not after the renders */
            return ydoc_fail(d, r, L->e, "reference: %s: %zu of its %zu values are NaN or infinite",
                             tmp.reference, bad, n);
        if (w != c->scenes[0].width || h != c->scenes[0].height)
            return ydoc_fail(d, r, L->e, "reference: image is %dx%d but the job renders %dx%d", w, h,
                             c->scenes[0].width, c->scenes[0].height);
        c->scenes[0].ref_kind = COMPARE_REF_IMAGE;
        return 0;
    }
    if (r->type != YAML_MAPPING_NODE)
        return ydoc_fail(
            d, r, L->e,
            "reference: must be an image file or job settings, e.g. { sampler: %s, threshold: 0.5 }",
            sampler_kind_name(SAMPLER_JITTER));
    if (compare_keys_check(&L->d, r, "reference", NULL, L->e) < 0)
        return -1;
    for (int s = 0; s < c->n_scenes; s++) {
        struct compare_scene *cs = &c->scenes[s];
        cs->ref_kind = COMPARE_REF_SETTINGS;
        cs->ref_job = L->scene_base[s];
        cs->ref_job.spec.seed = COMPARE_REF_SEED;
        for (int i = 0; ymap_pair(d, r, i, &k, &v); i++)
            if (job_apply(&cs->ref_job, d, k, v, L->e) < 0)
                return -1;
        if (job_finish(&cs->ref_job, d, L->e) < 0 ||
            job_limits_samples(&cs->ref_job, cs->width, cs->height, L->e) < 0)
            return -1;
    }
    return 0;
}

/* The image's file name: <scene>-<variant>-t<threshold>[-<swept key><value>...]-s<seed>.png */
static int file_name(struct compare_loading *L, const struct compare_item *it, char *out, size_t n)
{
    struct compare *c = L->c;
    char mid[256] = "", t[32];
    yaml_node_t *k, *v;
    snprintf(t, sizeof t, "%g", it->job.spec.pixel.threshold);
    compare_keys_append(mid, sizeof mid, "threshold", t);
    for (int i = 0; L->sweep && ymap_pair(&L->d, L->sweep, i, &k, &v); i++) {
        const char *val = yscalar(yseq_item(&L->d, v, it->point));
        if (strcmp(yscalar(k), "threshold"))
            compare_keys_append(mid, sizeof mid, yscalar(k), val ? val : "list");
    }
    int len = snprintf(out, n, "%s-%s-%s-s%llu.png", c->scenes[it->scene].name, c->variants[it->variant], mid,
                       (unsigned long long)c->seeds[it->seed]);
    return len > 0 && (size_t)len < n ? 0 : -1;
}

/* The point's label for people: "threshold 5, light_threshold 10" (or "as set" with no sweep). */
static void point_label(struct compare_loading *L, int p, char *out, size_t n)
{
    yaml_node_t *k, *v;
    snprintf(out, n, "%s", L->sweep ? "" : "as set");
    for (int i = 0; L->sweep && ymap_pair(&L->d, L->sweep, i, &k, &v); i++) {
        size_t len = strlen(out);
        const char *val = yscalar(yseq_item(&L->d, v, p));
        snprintf(out + len, n - len, "%s%s %s", i ? ", " : "", yscalar(k), val ? val : "(list)");
    }
}

/* One combination's job: scene base, the variant's keys, the sweep point's values, the seed. */
static int expand_one(struct compare_loading *L, struct compare_item *it)
{
    struct ydoc *d = &L->d;
    struct compare *c = L->c;
    yaml_node_t *var = yseq_item(d, L->variants, it->variant), *k, *v;
    struct job *j = &it->job;
    *j = L->scene_base[it->scene];
    for (int i = 0; ymap_pair(d, var, i, &k, &v); i++)
        if (strcmp(yscalar(k), "label") && job_apply(j, d, k, v, L->e) < 0)
            return -1;
    for (int i = 0; L->sweep && ymap_pair(d, L->sweep, i, &k, &v); i++)
        if (strcmp(yscalar(k), "spp") && job_apply(j, d, k, yseq_item(d, v, it->point), L->e) < 0)
            return -1;
    yaml_node_t *spp = L->sweep ? ymap_get(d, L->sweep, "spp") : NULL; /* once the sampler is known */
    if (spp && compare_spp_apply(j, d, yseq_item(d, spp, it->point), L->e) < 0)
        return -1;
    j->spec.seed = c->seeds[it->seed];
    job_mark(j, "output", NULL); /* the study names its images */
    job_mark(j, "format", NULL);
    j->format = IMG_PNG;
    if (job_finish(j, d, L->e) < 0)
        return -1;
    const struct compare_scene *cs = &c->scenes[it->scene];
    if (file_name(L, it, j->output, sizeof j->output) < 0)
        return ydoc_fail(d, var, L->e, "variant: the image name %s-%s-... is too long (shorten its label)",
                         cs->name, c->variants[it->variant]);
    j->float_copy = 1; /* scored, and averaged across seeds, in linear radiance */
    if (job_limits_samples(j, cs->width, cs->height, L->e) < 0)
        return -1;
    yaml_node_t *at = var; /* a clash comes from a repeated sweep value or variant */
    if (L->sweep && ymap_pair(d, L->sweep, 0, &k, &v))
        at = yseq_item(d, v, it->point);
    for (int i = 0; i < it - c->items; i++)
        if (!strcmp(c->items[i].job.output, j->output))
            return ydoc_fail(d, at, L->e,
                             "%s: two combinations would write this image (a repeated sweep value?)",
                             j->output);
    return 0;
}

int compare_expand_items(struct compare_loading *L, yaml_node_t *root)
{
    struct compare *c = L->c;
    double n = (double)c->n_scenes * c->n_variants * c->n_points * c->n_seeds;
    if (n > COMPARE_MAX_ITEMS)
        return ydoc_fail(&L->d, root, L->e,
                         "compare job: %d scenes x %d variants x %d sweep points x %d seeds is %.0f "
                         "images (limit %d)",
                         c->n_scenes, c->n_variants, c->n_points, c->n_seeds, n, COMPARE_MAX_ITEMS);
    c->n_items = (int)n;
    c->items = calloc((size_t)c->n_items, sizeof *c->items);
    c->points = calloc((size_t)c->n_points, sizeof *c->points);
    if (!c->items || !c->points || study_results_init(&c->results, c->n_items, c->n_scenes) < 0)
        return err_set(L->e, L->d.file, 0, 0, "out of memory");
    for (int p = 0; p < c->n_points; p++)
        point_label(L, p, c->points[p], sizeof c->points[p]);
    for (int s = 0; s < c->n_scenes; s++)
        for (int v = 0; v < c->n_variants; v++)
            for (int p = 0; p < c->n_points; p++)
                for (int k = 0; k < c->n_seeds; k++) {
                    struct compare_item *it = &c->items[compare_index(c, s, v, p, k)];
                    *it = (struct compare_item){.scene = s, .variant = v, .point = p, .seed = k};
                    snprintf(it->job.name, sizeof it->job.name, "%s", c->name);
                    if (expand_one(L, it) < 0)
                        return -1;
                }
    return 0;
}
