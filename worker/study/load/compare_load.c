/* compare_load: reading a compare job's keys, scenes, seeds, sweep and variants, with every
   check done before anything renders (compare_expand.c makes the combinations). */
#include "compare_load.h"
#include "compare_expand.h"
#include "compare_spp.h"
#include "compare_keys.h"
#include "compare_mask.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "job/outdir.h"
#include "scenefile/scene_load.h"
#include "scenefile/yget.h"

/* Scene s read once (its parse kept for the renders) and checked; its size: the job's width,
   height or width / the camera's aspect (as run_job does). */
static int scene_size(struct compare_loading *L, int s, yaml_node_t *at)
{
    struct compare_scene *cs = &L->c->scenes[s];
    const struct job *j = &L->scene_base[s];
    struct scene_file sf = {0};
    if (!(cs->input = study_inputs_scene(L->c->inputs, j->scene_path, L->e)) ||
        scene_load_src(&cs->input->src, &sf, L->e) < 0)
        return -1;
    cs->width = j->spec.width;
    long h = j->spec.height ? j->spec.height : lround(j->spec.width / sf.aspect);
    scene_file_free(&sf);
    cs->height = h < 1 ? 1 : (int)h;
    if (h > IMAGE_MAX_SIDE)
        return ydoc_fail(&L->d, at, L->e, "height: width / aspect gives %ld rows (limit %d)", h,
                         IMAGE_MAX_SIDE);
    return 0;
}

static int load_scenes(struct compare_loading *L, yaml_node_t *root)
{
    struct ydoc *d = &L->d;
    yaml_node_t *list = ymap_get(d, root, "scenes"), *one = ymap_get(d, root, "scene");
    if (list && one)
        return ydoc_fail(d, list, L->e, "scenes: give either scene or scenes, not both");
    if (!list && !one)
        return ymap_missing(d, root, ymap_get_raw(d, root, "scene") ? "scene" : "scenes", L->e,
                            "scenes: missing (list the scenes to compare, e.g. scenes: [checker])");
    int n = list ? yseq_len(list) : 1;
    if (n < 1)
        return ydoc_fail(d, list, L->e, "scenes: must be a non-empty list of scene names or files");
    L->c->n_scenes = n;
    L->c->scenes = calloc((size_t)n, sizeof *L->c->scenes);
    L->scene_base = calloc((size_t)n, sizeof *L->scene_base);
    if (!L->c->scenes || !L->scene_base)
        return err_set(L->e, L->d.file, 0, 0, "out of memory");
    for (int s = 0; s < n; s++) {
        yaml_node_t *item = list ? yseq_item(d, list, s) : one, *name = item, *mask = L->mask;
        L->scene_base[s] = L->base;
        if (list && (compare_mask_item(d, item, &name, &mask, L->e) < 0 ||
                     compare_keys_apply(&L->scene_base[s], d, "scene", name, L->e) < 0))
            return -1;
        mask = mask ? mask : L->mask;
        char stem[JOB_PATH_MAX];
        outdir_stem(L->scene_base[s].scene_path, stem, sizeof stem);
        if (strlen(stem) >= sizeof L->c->scenes[s].name) /* never cut: two scenes would share a name */
            return ydoc_fail(d, item, L->e,
                             "scenes: %s: its stem is %zu bytes, over the %zu that name a scene's outputs "
                             "(rename the file)",
                             L->scene_base[s].scene_path, strlen(stem), sizeof L->c->scenes[s].name - 1);
        snprintf(L->c->scenes[s].name, sizeof L->c->scenes[s].name, "%s", stem);
        for (int t = 0; t < s; t++)
            if (!strcmp(L->c->scenes[t].name, L->c->scenes[s].name))
                return strcmp(L->scene_base[t].scene_path, L->scene_base[s].scene_path)
                           ? ydoc_fail(d, item, L->e,
                                       "scenes: %s and %s are both named \"%s\" (a scene is named by its "
                                       "file's stem, and so are its outputs): rename one of the files",
                                       L->scene_base[t].scene_path, L->scene_base[s].scene_path,
                                       L->c->scenes[s].name)
                           : ydoc_fail(d, item, L->e, "scenes: \"%s\" is listed twice", L->c->scenes[s].name);
        if (scene_size(L, s, item) < 0 || compare_mask_load(d, mask, L->c->path, &L->c->scenes[s], L->e) < 0)
            return -1;
    }
    return 0;
}

static int load_seeds(struct compare_loading *L, yaml_node_t *root)
{
    struct ydoc *d = &L->d;
    yaml_node_t *list = ymap_get(d, root, "seeds");
    if (list && ymap_get(d, root, "seed"))
        return ydoc_fail(d, list, L->e, "seeds: give either seed or seeds, not both");
    int n = list ? yseq_len(list) : 1;
    if (n < 1)
        return ydoc_fail(d, list, L->e,
                         "seeds: must be a non-empty list of whole numbers, e.g. seeds: [1, 2, 3]");
    L->c->n_seeds = n;
    if (!(L->c->seeds = calloc((size_t)n, sizeof *L->c->seeds)))
        return err_set(L->e, d->file, 0, 0, "out of memory");
    if (!list) {
        L->c->seeds[0] = L->base.spec.seed;
        return 0;
    }
    for (int i = 0; i < n; i++) {
        long v;
        yaml_node_t *item = yseq_item(d, list, i);
        const struct render_spec_row *seed = render_spec_find("seed"); /* a seed's range, once */
        if (yget_long(d, item, "seeds", seed->lo, seed->hi, &v, L->e) < 0)
            return -1;
        for (int k = 0; k < i; k++)
            if (L->c->seeds[k] == (uint64_t)v)
                return ydoc_fail(d, item, L->e, "seeds: %ld is listed twice", v);
        L->c->seeds[i] = (uint64_t)v;
    }
    return 0;
}

static int load_sweep(struct compare_loading *L)
{
    struct ydoc *d = &L->d;
    yaml_node_t *sw = L->sweep, *k, *v;
    L->c->n_points = 1;
    if (!sw)
        return 0;
    if (sw->type != YAML_MAPPING_NODE || !ymap_pair(d, sw, 0, &k, &v))
        return ydoc_fail(
            d, sw, L->e,
            "sweep: must map a job key to a list of values, e.g. sweep: { threshold: [20, 10, 5, 2] }");
    if (compare_keys_check(&L->d, sw, "sweep", "spp", L->e) < 0)
        return -1;
    yaml_node_t *spp = NULL;
    for (int i = 0; ymap_pair(d, sw, i, &k, &v); i++)
        spp = strcmp(yscalar(k), "spp") ? spp : k;
    if (spp && ymap_get(d, sw, "threshold"))
        return ydoc_fail(d, spp, L->e,
                         "spp: and threshold: both set the camera sampler's threshold: sweep one of them");
    int n = -1;
    for (int i = 0; ymap_pair(d, sw, i, &k, &v); i++) {
        const char *key = yscalar(k);
        int len = yseq_len(v);
        if (len < 1)
            return ydoc_fail(d, v, L->e,
                             "%s: the sweep needs a non-empty list of values, e.g. [20, 10, 5, 2]", key);
        if (n >= 0 && len != n)
            return ydoc_fail(d, v, L->e,
                             "%s: swept keys step together, so their lists must be as long (%d, not %d)", key,
                             n, len);
        n = len;
        size_t used = strlen(L->c->sweep_keys);
        if (strcmp(key, "spp"))
            snprintf(L->c->sweep_keys + used, sizeof L->c->sweep_keys - used, "%s%s", i ? ", " : "", key);
        else
            snprintf(L->c->sweep_keys + used, sizeof L->c->sweep_keys - used, "%s" COMPARE_SPP_SWEEP_NOTE,
                     i ? ", " : "", sampler_kind_name(SAMPLER_POISSON));
    }
    L->c->n_points = n;
    return 0;
}

/* A variant's label: its `label:`, else built from its keys ("poisson-pool64"). */
static int variant_label(struct compare_loading *L, yaml_node_t *var, int index, char *out, size_t n)
{
    struct ydoc *d = &L->d;
    yaml_node_t *lab = ymap_get(d, var, "label"), *k, *v;
    const char *s;
    out[0] = 0;
    if (lab) {
        if (yget_string(d, lab, "label", &s, L->e) < 0)
            return -1;
        for (const char *p = s; *p; p++)
            if ((!isalnum((unsigned char)*p) && !strchr("-_", *p)) || p - s >= (long)n - 1)
                return ydoc_fail(d, lab, L->e,
                                 "label: must be letters, digits, '-' or '_' (at most %d), got \"%.40s\"",
                                 (int)n - 1, s);
        snprintf(out, n, "%s", s);
        return 0;
    }
    const char *pix = yscalar(ymap_get(d, var, "sampler")),
               *light = yscalar(ymap_get(d, var, "light_sampler"));
    if (pix)
        compare_keys_append(out, n, "sampler", pix);
    if (light && (!pix || strcmp(pix, light)))
        compare_keys_append(out, n, "light_sampler", light);
    for (int i = 0; ymap_pair(d, var, i, &k, &v); i++)
        if (strcmp(yscalar(k), "sampler") && strcmp(yscalar(k), "light_sampler"))
            compare_keys_append(out, n, yscalar(k), yscalar(v) ? yscalar(v) : "list");
    if (!out[0])
        snprintf(out, n, "variant%d", index + 1);
    return 0;
}

static int load_variants(struct compare_loading *L)
{
    struct ydoc *d = &L->d;
    yaml_node_t *list = L->variants, *k, *v;
    int n = yseq_len(list);
    if (!list) /* written, as jobfile_open saw, but null */
        return ymap_missing(d, ydoc_root(d), "variants", L->e, "variants: missing");
    if (n < 1)
        return ydoc_fail(d, list, L->e,
                         "variants: must be a non-empty list of job settings, e.g. - { sampler: %s }",
                         sampler_kind_name(SAMPLER_JITTER));
    L->c->n_variants = n;
    if (!(L->c->variants = calloc((size_t)n, sizeof *L->c->variants)))
        return err_set(L->e, d->file, 0, 0, "out of memory");
    for (int i = 0; i < n; i++) {
        yaml_node_t *var = yseq_item(d, list, i);
        if (compare_keys_check(&L->d, var, "variant", "label", L->e) < 0)
            return -1;
        for (int p = 0; ymap_pair(d, var, p, &k, &v); p++)
            if (L->sweep && (ymap_get(d, L->sweep, yscalar(k)) ||
                             (!strcmp(yscalar(k), "threshold") && ymap_get(d, L->sweep, "spp"))))
                return ydoc_fail(d, k, L->e, "%s: swept (sweep: %s), so a variant cannot set it", yscalar(k),
                                 ymap_get(d, L->sweep, yscalar(k)) ? yscalar(k) : "spp");
        if (variant_label(L, var, i, L->c->variants[i], sizeof L->c->variants[i]) < 0)
            return -1;
        for (int j = 0; j < i; j++)
            if (!strcmp(L->c->variants[j], L->c->variants[i]))
                return ydoc_fail(d, var, L->e,
                                 "variants: two variants are labelled \"%s\" (give one a label:)",
                                 L->c->variants[i]);
    }
    return 0;
}

struct compare *compare_load(const char *path, struct err *e)
{
    struct ydoc d;
    struct compare *c = ydoc_load(&d, path, e) < 0 ? NULL : compare_load_doc(&d, path, e);
    ydoc_free(&d);
    return c;
}

struct compare *compare_load_doc(const struct ydoc *doc, const char *path, struct err *e)
{
    return compare_load_in(doc, path, NULL, e);
}

struct compare *compare_load_in(const struct ydoc *doc, const char *path, struct study_inputs *in,
                                struct err *e)
{
    /* the document borrowed: read through L.d, freed by its owner */
    struct compare_loading L = {.d = *doc, .e = e};
    const char *extra[] = {"scenes", "variants", "sweep", "seeds", "mask", "rank_by"};
    int ok = 0;
    if (!(L.c = calloc(1, sizeof *L.c)) || !(L.c->inputs = in ? in : study_inputs_new())) {
        free(L.c);
        err_set(e, path, 0, 0, "out of memory");
        return NULL;
    }
    L.c->owns_inputs = !in;
    snprintf(L.c->path, sizeof L.c->path, "%s", path);
    job_defaults(&L.base, path);
    yaml_node_t *root = ydoc_root(&L.d), *k, *v;
    const char *keys[JOB_KEYS_MAX + 1 + sizeof extra / sizeof *extra];
    int nk = job_key_list(keys, JOB_KEYS_MAX + 1);
    for (size_t i = 0; i < sizeof extra / sizeof *extra; i++)
        keys[nk++] = extra[i];
    keys[nk] = NULL;
    if (ymap_check(&L.d, root, keys, "compare job", e) < 0)
        goto done;
    for (int i = 0; ymap_pair(&L.d, root, i, &k, &v); i++) {
        const char *key = yscalar(k), *why = compare_keys_forbidden(key, "top");
        if (why) {
            ydoc_fail(&L.d, k, e, "%s: not allowed in a compare job: %s", key, why);
            goto done;
        }
        if (!strcmp(key, "reference"))
            L.reference = v;
        else if (!strcmp(key, "variants"))
            L.variants = v;
        else if (!strcmp(key, "sweep"))
            L.sweep = v;
        else if (!strcmp(key, "mask"))
            L.mask = v;
        else if (!strcmp(key, "rank_by")) {
            const char *by = yscalar(v);
            if (!by || (strcmp(by, "mean") && strcmp(by, "median"))) {
                ydoc_fail(&L.d, v, e, "rank_by: must be mean or median, got %s", by ? by : "a collection");
                goto done;
            }
            L.c->rank_by = strcmp(by, "median") ? VERDICT_RANK_MEAN : VERDICT_RANK_MEDIAN;
        } else if (strcmp(key, "scenes") && strcmp(key, "seeds") && job_apply(&L.base, &L.d, k, v, e) < 0)
            goto done;
    }
    if (job_check_stem(&L.base, e) < 0)
        goto done;
    snprintf(L.c->name, sizeof L.c->name, "%s", L.base.name);
    if (load_scenes(&L, root) < 0 || load_seeds(&L, root) < 0 || load_sweep(&L) < 0 ||
        load_variants(&L) < 0 || compare_expand_reference(&L) < 0 || compare_expand_items(&L, root) < 0)
        goto done;
    for (int i = 0; i < L.c->n_items; i++) /* every image is scored against its scene's reference */
        L.c->items[i].job.reference[0] = 0;
    ok = 1;
done:
    free(L.scene_base);
    if (!ok) {
        compare_free(L.c);
        return NULL;
    }
    return L.c;
}
