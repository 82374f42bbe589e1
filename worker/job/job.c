/* job: reading a job file's keys into a struct job, with strict validation and defaults. */
#include "job.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "job_path.h"
#include "image/imgio.h"
#include "outdir.h"
#include "base/fileio.h"
#include "scenefile/yget.h"

/* The job's own keys; a render's are render_spec's rows. */
static const char *const job_keys[] = {"name",      "scene",    "processes",   "format", "output",
                                       "reference", "priority", "entry_cpu_s", NULL};
#define JOB_OWN_KEYS ((int)(sizeof job_keys / sizeof job_keys[0]) - 1)

int job_key_list(const char **out, int cap)
{
    int n = 0, rows;
    const struct render_spec_row *r = render_spec_rows(&rows);
    for (int i = 0; i < JOB_OWN_KEYS + rows && n < cap - 1; i++)
        out[n++] = i < JOB_OWN_KEYS ? job_keys[i] : r[i - JOB_OWN_KEYS].key;
    out[n] = NULL;
    return n;
}

/* key's index in job_key_list, or -1. */
static int key_index(const char *key)
{
    const char *keys[JOB_KEYS_MAX + 1];
    for (int i = 0, n = job_key_list(keys, JOB_KEYS_MAX + 1); i < n; i++)
        if (!strcmp(keys[i], key))
            return i;
    return -1;
}

const int *job_at(const struct job *j, const char *key)
{
    static const int absent[2] = {0, 0};
    int i = key_index(key);
    return i < 0 ? absent : j->pos.at[i];
}

void job_mark(struct job *j, const char *key, const yaml_node_t *v)
{
    int i = key_index(key);
    if (i >= 0) {
        j->pos.at[i][0] = v ? (int)v->start_mark.line + 1 : 0;
        j->pos.at[i][1] = v ? (int)v->start_mark.column + 1 : 0;
    }
}

void job_defaults(struct job *j, const char *path)
{
    memset(j, 0, sizeof *j);
    snprintf(j->path, sizeof j->path, "%s", path);
    outdir_stem(path, j->name, sizeof j->name);
    render_spec_defaults(&j->spec);
    j->processes = 2;
    j->format = IMG_PNG;
}

/* key's value at v, a name used as a directory or file name, into out (JOB_NAME_MAX bytes):
   letters, digits, '-', '_', '.'; not starting with '.' (".", "..", and hidden folders: .cache
   holds compare references). what: the message's words for such a name. */
static int get_safe_name(struct ydoc *d, yaml_node_t *v, const char *key, const char *what, char *out,
                         struct err *e)
{
    const char *s;
    if (yget_string(d, v, key, &s, e) < 0)
        return -1;
    if (!*s || *s == '.' || strlen(s) >= JOB_NAME_MAX ||
        strspn(s, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.") != strlen(s))
        return ydoc_fail(
            d, v, e,
            "%s: must be %sletters, digits, '-', '_' or '.' (at most %d, not starting with '.'), "
            "got \"%.40s\"",
            key, what, JOB_NAME_MAX - 1, s);
    snprintf(out, JOB_NAME_MAX, "%s", s);
    return 0;
}

const char *job_unknown_sampler(const char *s, char *buf, size_t n)
{
    const char *near = ystr_nearest(s, sampler_kind_names(), -1);
    char list[256];
    if (near)
        snprintf(buf, n, "unknown sampler \"%.40s\" (did you mean \"%s\"?)", s, near);
    else
        snprintf(buf, n, "unknown sampler \"%.40s\" (expected one of %s)", s,
                 sampler_kind_list(", ", list, sizeof list));
    return buf;
}

static int get_threshold(struct ydoc *d, yaml_node_t *v, const struct render_spec_row *r, double *out,
                         struct err *e)
{
    const char *s = yscalar(v);
    char want[64];
    render_spec_expected(r, want, sizeof want);
    double t = 0;
    int rc = yget_double(d, v, r->key, &t, e), failed = rc < 0; /* e->msg is set only when it failed */
    int quoted_number = failed && strstr(e->msg, YQUOTED_NOTE) != NULL;
    if (rc == YGET_UNDERFLOW) /* yget_double's own message says it better */
        return -1;
    if (!s)
        return ydoc_fail(d, v, e, "%s: must be %s, got a %s", r->key, want,
                         v->type == YAML_SEQUENCE_NODE ? "list" : "mapping");
    if (failed || !render_spec_in_range(r, t))
        return ydoc_fail(d, v, e, "%s: must be %s, got \"%.40s\"%s", r->key, want, s,
                         quoted_number ? YQUOTED_NOTE : "");
    *out = t;
    return 0;
}

/* An output's extension names the format written (any case; none: format:, else png): one that
   names no format we write is an error at v, not a PNG under that name. The sidecar's own
   extension gets its own message. */
static int check_output_ext(struct ydoc *d, yaml_node_t *v, const char *out, struct err *e)
{
    enum img_format f;
    size_t len = strlen(out);
    char list[128];
    img_format_list(list, sizeof list);
    if (len > 5 && !strcmp(out + len - 5, ".json")) /* the sidecar is the output's stem + ".json" */
        return ydoc_fail(
            d, v, e,
            "output: %s would be overwritten by its own sidecar (give it an image format's extension: %s)",
            out, list);
    if (img_format_of_file(out, &f) >= 0)
        return 0;
    return ydoc_fail(d, v, e,
                     "output: %s: the extension \"%.20s\" names no image format this worker writes (%s)", out,
                     strrchr(out, '.'), list);
}

/* output: one plain file name whose extension names a format written (none: format:), or a list
   of such names, each with its extension, of distinct formats and one stem (the sidecar's). */
static int get_outputs(struct job *j, struct ydoc *d, yaml_node_t *v, struct err *e)
{
    const int list = v->type == YAML_SEQUENCE_NODE, n = list ? yseq_len(v) : 1;
    if (n < 1 || n > JOB_OUTPUTS_MAX)
        return ydoc_fail(d, v, e, "output: a list holds 1 to %d image names (one per format), got %d",
                         JOB_OUTPUTS_MAX, n);
    enum img_format seen[JOB_OUTPUTS_MAX];
    for (int i = 0; i < n; i++) {
        yaml_node_t *item = list ? yseq_item(d, v, i) : v;
        char *out = i == 0 ? j->output : j->more_output[i - 1];
        if (get_safe_name(d, item, "output", "a plain file name of ", out, e) < 0 ||
            check_output_ext(d, item, out, e) < 0)
            return -1;
        if (list && img_format_of_file(out, &seen[i]) <= 0)
            return ydoc_fail(d, item, e, "output: %s: in a list each image needs its format's extension",
                             out);
        for (int k = 0; k < i; k++)
            if (seen[k] == seen[i])
                return ydoc_fail(d, item, e, "output: two %s images in one list (one per format)",
                                 img_format_name(seen[i]));
        if (i > 0) {
            /* one stem for all: the sidecar X.json sits beside every image X.<ext> */
            size_t stem = (size_t)(strrchr(j->output, '.') - j->output);
            if (strlen(out) <= stem || strncmp(out, j->output, stem) || out[stem] != '.' ||
                strchr(out + stem + 1, '.'))
                return ydoc_fail(d, item, e,
                                 "output: %s: the images of a list share one name before the extension "
                                 "(%.*s, the sidecar's)",
                                 out, (int)stem, j->output);
            j->more_format[i - 1] = seen[i];
        }
    }
    if (list)
        j->n_more = n - 1;
    return 0;
}

/* A render setting: row r's value at v into s, checked against the row's type and range. */
static int apply_spec(struct render_spec *s, const struct render_spec_row *r, struct ydoc *d, yaml_node_t *v,
                      struct err *e)
{
    long n = 0;
    int yes = 0;
    const char *text;
    char want[256];
    if (r->type == RS_THRESHOLD)
        return get_threshold(d, v, r, render_spec_threshold(s, r), e);
    if (r->type == RS_SAMPLER || r->type == RS_CHOICE) {
        if (yget_string(d, v, r->key, &text, e) < 0)
            return -1;
        if (render_spec_set_text(s, r, text) == 0)
            return 0;
        if (r->type == RS_SAMPLER)
            return ydoc_fail(d, v, e, "%s: %s", r->key, job_unknown_sampler(text, want, sizeof want));
        return ydoc_fail(d, v, e, "%s: must be %s, got \"%.40s\"", r->key,
                         render_spec_expected(r, want, sizeof want), text);
    }
    if (r->type == RS_BOOL ? yget_bool(d, v, r->key, &yes, e) < 0
                           : yget_long(d, v, r->key, r->lo, r->hi, &n, e) < 0)
        return -1;
    render_spec_put(s, r, (uint64_t)(int64_t)(r->type == RS_BOOL ? yes : n));
    return 0;
}

int job_apply(struct job *j, struct ydoc *d, yaml_node_t *key, yaml_node_t *v, struct err *e)
{
    const char *k = yscalar(key);
    const char *s;
    long n;
    const struct render_spec_row *row = render_spec_find(k);
    job_mark(j, k, v);
    if (row)
        return apply_spec(&j->spec, row, d, v, e);
    if (!strcmp(k, "name")) {
        return get_safe_name(d, v, k, "", j->name, e);
    } else if (!strcmp(k, "scene")) {
        if (yget_string(d, v, k, &s, e) < 0)
            return -1;
        char tried[4 * JOB_PATH_MAX + 32], hint[JOB_PATH_MAX + 32];
        if (job_path_scene(j, s, tried, sizeof tried) < 0) {
            const char *kind = fileio_kind(j->scene_path); /* there, but a FIFO, a device, a folder */
            if (kind)
                return ydoc_fail(d, v, e,
                                 "scene: %s is %s, not a scene file (a scene file is a regular file)",
                                 j->scene_path, kind);
            return ydoc_fail(d, v, e, "scene: no scene file at %s%s%s", j->scene_path, tried,
                             job_path_scene_hint(j, s, hint, sizeof hint));
        }
    } else if (!strcmp(k, "processes")) {
        if (yget_long(d, v, k, 1, 256, &n, e) < 0)
            return -1;
        j->processes = (int)n;
    } else if (!strcmp(k, "entry_cpu_s")) {
        if (yget_double(d, v, k, &j->entry_cpu_s, e) < 0)
            return -1;
        if (!(j->entry_cpu_s >= 0.01 && j->entry_cpu_s <= 1e6))
            return ydoc_fail(d, v, e, "%s: must be in [0.01, 1e6] CPU seconds, got %s", k, yscalar(v));
    } else if (!strcmp(k, "priority")) {
        if (yget_long(d, v, k, -1000000, 1000000, &n, e) < 0)
            return -1;
        j->priority = (int)n;
    } else if (!strcmp(k, "format")) {
        if (yget_string(d, v, k, &s, e) < 0)
            return -1;
        if (img_format_parse(s, &j->format) < 0) {
            char list[128];
            img_format_list(list, sizeof list);
            return ydoc_fail(d, v, e, "format: must be %s, got \"%.40s\"", list, s);
        }
    } else if (!strcmp(k, "output")) {
        return get_outputs(j, d, v, e);
    } else if (!strcmp(k, "reference")) {
        if (yget_string(d, v, k, &s, e) < 0)
            return -1;
        job_path_resolve(j->path, s, j->reference, sizeof j->reference);
        const char *kind = fileio_kind(j->reference);
        if (kind && !job_path_is_file(j->reference))
            return ydoc_fail(d, v, e, "reference: %s is %s, not an image file (an image is a regular file)",
                             j->reference, kind);
        if (!kind)
            return ydoc_fail(d, v, e, "reference: no image file at %s", j->reference);
    }
    return 0;
}

/* Refuse a threshold whose sets would not fit the per-set limit (a set is held whole in memory, one
   for the pixel and one per sampled light; Poisson's counts Bridson's grid cells, about three per
   point): the count, the limit, why, and the smallest threshold that fits. */
static int check_set_size(const struct job *j, const struct sampler_spec *sp, const char *key, struct err *e)
{
    const enum sampler_kind k = sp->kind;
    const double t = sp->threshold;
    const int *pos = job_at(j, key);
    size_t n = sampler_capacity(k, t);
    if (n <= SAMPLER_MAX_POINTS)
        return 0;
    char count[64];
    if (n == SIZE_MAX) /* saturated: the count itself does not fit */
        snprintf(count, sizeof count, "more than %zu", (size_t)SAMPLER_MAX_POINTS);
    else
        snprintf(count, sizeof count, "%zu", n);
    const char *what = sampler_capacity_unit(k);
    return err_set(e, j->path, pos[0], pos[1],
                   "%s: %g would need %s %s per %s set (limit %d per set, each set held whole in memory); "
                   "the smallest %s %s is %g",
                   key, t, count, what, sampler_kind_name(k), SAMPLER_MAX_POINTS, sampler_kind_name(k), key,
                   sampler_smallest_threshold(k));
}

int job_height(const struct job *j, double aspect)
{
    if (j->spec.height)
        return j->spec.height;
    int h = (int)lround(j->spec.width / aspect); /* the aspect is at least 0.01: within an int */
    return h < 1 ? 1 : h;
}

int job_check_stem(const struct job *j, struct err *e)
{
    char stem[JOB_PATH_MAX];
    outdir_stem(j->path, stem, sizeof stem);
    if (job_at(j, "name")[0] || strlen(stem) < JOB_NAME_MAX)
        return 0;
    return err_set(
        e, j->path, 1, 1,
        "name: the file's stem is %zu bytes, over the %d a name holds (it is never cut short); give "
        "the job a name:",
        strlen(stem), JOB_NAME_MAX - 1);
}

int job_finish(struct job *j, struct ydoc *d, struct err *e)
{
    (void)d;
    if (job_check_stem(j, e) < 0)
        return -1;
    /* A name from the file's stem ("..yaml" gives ".", "...yaml" "..") names the output folder too:
       the rule for name: keeps it inside --out and off hidden folders (.cache). */
    if (!job_at(j, "name")[0] && (!j->name[0] || j->name[0] == '.'))
        return err_set(e, j->path, 1, 1,
                       "name: the file's stem \"%s\" cannot name the output folder (it starts with '.'); "
                       "give the job a name:",
                       j->name);
    /* under sampler_dims: all every light point comes from the pixel sampler's sets: a light
       sampler or threshold would be silently ignored */
    const int has_light_sampler = job_at(j, "light_sampler")[0] != 0;
    const int *light_pos = job_at(j, has_light_sampler ? "light_sampler" : "light_threshold");
    if (j->spec.dims_all && light_pos[0])
        return err_set(e, j->path, light_pos[0], light_pos[1],
                       "%s: has no effect with sampler_dims: all (line %d), whose light points come from the "
                       "pixel sampler's sets; remove it or use sampler_dims: pixel_light",
                       has_light_sampler ? "light_sampler" : "light_threshold", job_at(j, "sampler_dims")[0]);
    if (!has_light_sampler)
        j->spec.light.kind = j->spec.pixel.kind;
    if (check_set_size(j, &j->spec.pixel, "threshold", e) < 0 ||
        check_set_size(j, &j->spec.light, "light_threshold", e) < 0)
        return -1;
    /* the output's extension (job_apply checked it names a format) and format: must agree */
    enum img_format ext;
    const int *format_pos = job_at(j, "format"), has_output = job_at(j, "output")[0] != 0;
    int has_ext = has_output && img_format_of_file(j->output, &ext) > 0;
    if (has_ext && format_pos[0] && ext != j->format)
        return err_set(e, j->path, format_pos[0], format_pos[1],
                       "format: %s contradicts the output's extension (%s); give one or make them agree",
                       img_format_name(j->format), j->output);
    if (has_ext)
        j->format = ext;
    if (!has_output)
        snprintf(j->output, sizeof j->output, "%s.%s", j->name, img_format_name(j->format));
    return 0;
}

const char *job_light_text(const struct job *j, char *buf, size_t n)
{
    const struct render_spec *s = &j->spec;
    if (!s->light_sampling)
        snprintf(buf, n, "no light sampling");
    else if (s->dims_all) /* the light sampler is never asked: render_path.h's path_decide */
        snprintf(buf, n, "light points from the %s sets (sampler_dims: all)",
                 sampler_kind_name(s->pixel.kind));
    else
        snprintf(buf, n, "light %s t=%g", sampler_kind_name(s->light.kind), s->light.threshold);
    return buf;
}

int job_from_doc(struct ydoc *d, const char *path, struct job *j, struct err *e)
{
    job_defaults(j, path);
    yaml_node_t *root = ydoc_root(d), *k, *v;
    const char *keys[JOB_KEYS_MAX + 1];
    job_key_list(keys, JOB_KEYS_MAX + 1);
    if (ymap_check(d, root, keys, "job", e) < 0)
        return -1;
    for (int i = 0; ymap_pair(d, root, i, &k, &v); i++)
        if (job_apply(j, d, k, v, e) < 0)
            return -1;
    if (!ymap_get(d, root, "scene"))
        return ymap_missing(d, root, "scene", e, "scene: missing (name a scene file, e.g. scene: checker)");
    return job_finish(j, d, e);
}
