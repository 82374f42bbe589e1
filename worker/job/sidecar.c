/* sidecar: the JSON record beside every image (job, machine, sampler settings, sample counts, rays, times,
   error) written, and read back with the YAML parser (JSON is YAML's flow syntax). */
#include "sidecar.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/fileio.h"
#include "base/json.h"
#include "scenefile/yamlx.h"

/* s with every byte outside printable ASCII replaced by '?' and surrounding spaces trimmed. */
static void clean(char *s)
{
    size_t n = strlen(s);
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t'))
        s[--n] = 0;
    size_t lead = strspn(s, " \t");
    memmove(s, s + lead, n - lead + 1);
    for (; *s; s++)
        if ((unsigned char)*s < 0x20 || (unsigned char)*s > 0x7e)
            *s = '?';
}

/* The value of /proc/cpuinfo's (text's) first line "key<tabs/spaces>: value" among keys, into out
   (unchanged when there is none). */
static void cpuinfo_value(const char *text, char *out, size_t n)
{
    static const char *const keys[] = {"model name", "Hardware", "cpu model", "Processor"};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++)
        for (const char *line = text; line && *line;
             line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
            size_t len = strlen(keys[k]);
            if (strncmp(line, keys[k], len) || !strchr(" \t:", line[len]))
                continue;
            const char *colon = strchr(line, ':'), *end = strchr(line, '\n');
            if (!colon || (end && colon > end))
                continue;
            snprintf(out, n, "%.*s", (int)((end ? end : colon + strlen(colon)) - colon - 1), colon + 1);
            clean(out);
            if (out[0])
                return;
        }
}

/* Where a render ran (CPU times of different machines do not compare): this machine's host name and
   CPU model (cpuinfo_value's), "unknown" when not found, printable ASCII only, into host and cpu
   (n bytes each). */
static void describe_machine(char *host, char *cpu, size_t n)
{
    snprintf(host, n, "unknown");
    snprintf(cpu, n, "unknown");
    char name[256];
    if (gethostname(name, sizeof name) == 0) {
        name[sizeof name - 1] = 0;
        snprintf(host, n, "%s", name);
        clean(host);
    }
    /* /proc files report no size: read the first 64 KiB (the first processor's lines come first) */
    static const size_t max = 64 * 1024;
    char *text = malloc(max + 1);
    FILE *f = text ? fopen("/proc/cpuinfo", "r") : NULL;
    if (f) {
        size_t len = fread(text, 1, max, f);
        text[len] = 0;
        fclose(f);
        cpuinfo_value(text, cpu, n);
    }
    free(text);
}

struct sidecar_work sidecar_work_of(const struct render_stats *st)
{
    return (struct sidecar_work){
        st->samples,      st->rays - st->shadow_rays, st->shadow_rays, st->pixel_points,
        st->light_points, st->padded_points,          st->pixels,      st->light_sets,
        st->padded_sets};
}

/* The sidecar's object "work": each count's key and field, in the order written; the writer and
   the reader both go by it. */
#define AT(field) offsetof(struct sidecar_work, field)
static const struct {
    const char *key;
    size_t at;
} work_keys[] = {{"camera_samples", AT(camera_samples)}, {"path_segments", AT(path_segments)},
                 {"shadow_rays", AT(shadow_rays)},       {"pixel_points", AT(pixel_points)},
                 {"light_points", AT(light_points)},     {"padded_points", AT(padded_points)},
                 {"pixel_sets", AT(pixel_sets)},         {"light_sets", AT(light_sets)},
                 {"padded_sets", AT(padded_sets)}};
#define N_WORK (sizeof work_keys / sizeof work_keys[0])

static uint64_t *work_count(struct sidecar_work *w, size_t i)
{
    return (uint64_t *)((char *)w + work_keys[i].at);
}

char *sidecar_json(const struct sidecar *s)
{
    const struct job *j = s->job;
    const struct procs_result *r = s->res;
    const struct render_stats *t = &r->total;
    struct json js;
    json_init(&js);
    json_begin_object(&js, NULL);
    json_string(&js, "worker_version", WORKER_VERSION);
    json_string(&js, "job", j->name);
    json_string(&js, "job_file", j->path);
    char hash[24];
    snprintf(hash, sizeof hash, "%016" PRIx64, j->hash);
    json_string(&js, "job_hash", hash);
    json_string(&js, "scene", j->scene_path);
    json_string(&js, "image", s->image);
    char host[128], cpu[128];
    describe_machine(host, cpu, sizeof host);
    json_string(&js, "host", host);
    json_string(&js, "cpu_model", cpu);
    struct render_spec spec = j->spec; /* at the size rendered */
    spec.width = s->width;
    spec.height = s->height;
    render_spec_json(&spec, &js);
    json_begin_array(&js, "size");
    json_uint(&js, NULL, (uint64_t)s->width);
    json_uint(&js, NULL, (uint64_t)s->height);
    json_end_array(&js);
    json_uint(&js, "processes", (uint64_t)r->processes);
    if (s->parts > 0)
        json_uint(&js, "parts", (uint64_t)s->parts);

    json_begin_object(&js, "samples");
    json_uint(&js, "total", t->samples);
    json_number(&js, "per_pixel_mean", t->pixels ? (double)t->samples / t->pixels : 0);
    json_uint(&js, "per_pixel_min", t->pixels ? t->spp_min : 0);
    json_uint(&js, "per_pixel_max", t->spp_max);
    json_end_object(&js);
    json_uint(&js, "light_sample_sets", t->light_sets);
    json_begin_object(&js, "rays");
    json_uint(&js, "camera", t->samples);
    json_uint(&js, "total", t->rays);
    json_end_object(&js);
    struct sidecar_work work = sidecar_work_of(t);
    json_begin_object(&js, "work");
    for (size_t i = 0; i < N_WORK; i++)
        json_uint(&js, work_keys[i].key, *work_count(&work, i));
    json_end_object(&js);

    json_begin_object(&js, "time");
    json_number(&js, "wall_s", r->wall_s);
    json_number(&js, "cpu_s", r->cpu_s);
    json_number(&js, "sampler_s", t->sampler_s);
    json_number(&js, "sampling_share", procs_sampling_share(r));
    json_number(&js, "ns_per_sample", t->samples ? r->cpu_s * 1e9 / (double)t->samples : 0);
    json_begin_array(&js, "per_process");
    for (int i = 0; i < r->processes; i++) {
        json_begin_object(&js, NULL);
        json_number(&js, "wall_s", r->proc[i].wall_s);
        json_number(&js, "cpu_s", r->proc[i].cpu_s);
        json_uint(&js, "pixels", r->proc[i].st.pixels);
        json_uint(&js, "samples", r->proc[i].st.samples);
        json_end_object(&js);
    }
    json_end_array(&js);
    json_end_object(&js);
    json_uint(&js, "peak_rss_kb", (uint64_t)r->peak_rss_kb);
    json_uint(&js, "nonfinite_samples", t->nonfinite); /* counted as zero, not dropped */
    if (s->error) {
        json_begin_object(&js, "error");
        json_string(&js, "reference", j->reference);
        json_string(&js, "domain", image_domain_name(s->error_domain));
        json_number(&js, "mse", s->error->mse);
        json_number(&js, "rmse", s->error->rmse);
        json_number(&js, "relmse", s->error->relmse);
        json_number(&js, "relmse_eps", METRICS_REL_EPS);
        json_number(&js, "relmse_robust", s->error->relmse_robust);
        json_number(&js, "relmse_robust_drop", METRICS_ROBUST_DROP);
        json_number(&js, "psnr", s->error->psnr);
        json_end_object(&js);
    }
    json_end_object(&js);
    if (js.text.oom) {
        json_free(&js);
        return NULL;
    }
    return js.text.buf;
}

/* The scalar text of key in mapping m: 1, or 0 and NULL when absent; -1 (e filled) when not a
   scalar. */
static int scalar_at(struct ydoc *d, yaml_node_t *m, const char *key, const char **out, struct err *e)
{
    yaml_node_t *v = ymap_get_raw(d, m, key);
    *out = NULL;
    if (!v)
        return 0;
    if (!(*out = yscalar(v)))
        return ydoc_fail(d, v, e, "%s: expected a value, got %s", key, ydoc_node_kind(v));
    if (strlen(*out) != v->data.scalar.length)
        return ydoc_fail(d, v, e, "%s: holds a NUL character", key);
    return 1;
}

static int string_at(struct ydoc *d, yaml_node_t *m, const char *key, char *out, size_t n, struct err *e)
{
    const char *s;
    if (scalar_at(d, m, key, &s, e) < 0)
        return -1;
    if (s && strlen(s) >= n)
        return ydoc_fail(d, ymap_get_raw(d, m, key), e, "%s: longer than %zu bytes", key, n - 1);
    snprintf(out, n, "%s", s ? s : "");
    return 0;
}

static int number_at(struct ydoc *d, yaml_node_t *m, const char *key, double *out, struct err *e)
{
    const char *s;
    char *end;
    int rc = scalar_at(d, m, key, &s, e);
    if (rc <= 0)
        return rc;
    if (!strcmp(s, "null")) {
        *out = NAN;
        return 0;
    }
    *out = strtod(s, &end);
    if (!*s || *end || !isfinite(*out))
        return ydoc_fail(d, ymap_get_raw(d, m, key), e, "%s: expected a number, got \"%.40s\"", key, s);
    return 0;
}

static int count_at(struct ydoc *d, yaml_node_t *m, const char *key, uint64_t *out, struct err *e)
{
    const char *s;
    char *end;
    int rc = scalar_at(d, m, key, &s, e);
    if (rc <= 0)
        return rc;
    errno = 0;
    *out = strtoull(s, &end, 10);
    if (!*s || *end || errno || strspn(s, "0123456789") != strlen(s))
        return ydoc_fail(d, ymap_get_raw(d, m, key), e, "%s: expected a whole number, got \"%.40s\"", key, s);
    return 0;
}

/* The hash's 16 hex digits, or has_hash 0. */
static int hash_at(struct ydoc *d, yaml_node_t *m, struct sidecar_info *out, struct err *e)
{
    char hex[32];
    if (string_at(d, m, "job_hash", hex, sizeof hex, e) < 0)
        return -1;
    if (strlen(hex) != 16 || strspn(hex, "0123456789abcdef") != 16)
        return 0;
    out->job_hash = strtoull(hex, NULL, 16);
    out->has_hash = 1;
    return 0;
}

/* The render's settings (render_spec's rows) into out->spec; a key absent keeps its default. */
static int spec_at(struct ydoc *d, yaml_node_t *m, struct sidecar_info *out, struct err *e)
{
    int n;
    const struct render_spec_row *rows = render_spec_rows(&n);
    render_spec_defaults(&out->spec);
    for (int i = 0; i < n; i++) {
        const char *s;
        char want[160];
        if (scalar_at(d, m, rows[i].key, &s, e) < 0)
            return -1;
        if (s && render_spec_set_text(&out->spec, &rows[i], s) < 0)
            return ydoc_fail(d, ymap_get_raw(d, m, rows[i].key), e, "%s: expected %s, got \"%.40s\"",
                             rows[i].key, render_spec_expected(&rows[i], want, sizeof want), s);
    }
    return 0;
}

static int fill(struct ydoc *d, struct sidecar_info *out, struct err *e)
{
    yaml_node_t *root = ydoc_root(d);
    if (!root || root->type != YAML_MAPPING_NODE)
        return ydoc_fail(d, root, e, "a sidecar holds one JSON object, got %s",
                         root ? ydoc_node_kind(root) : "nothing");
    yaml_node_t *samples = ymap_get(d, root, "samples"), *time = ymap_get(d, root, "time"),
                *error = ymap_get(d, root, "error"), *work = ymap_get(d, root, "work");
    const struct {
        const char *key;
        yaml_node_t *n;
    } parts[] = {{"samples", samples}, {"time", time}, {"error", error}, {"work", work}};
    for (size_t i = 0; i < sizeof parts / sizeof parts[0]; i++)
        if (parts[i].n && parts[i].n->type != YAML_MAPPING_NODE)
            return ydoc_fail(d, parts[i].n, e, "%s: expected an object, got %s", parts[i].key,
                             ydoc_node_kind(parts[i].n));
    out->has_error = error != NULL;
    out->has_work = work != NULL;
    for (size_t i = 0; i < N_WORK; i++)
        if (count_at(d, work, work_keys[i].key, work_count(&out->work, i), e) < 0)
            return -1;
    return spec_at(d, root, out, e) < 0 || string_at(d, root, "job", out->job, sizeof out->job, e) < 0 ||
                   string_at(d, root, "job_file", out->job_file, sizeof out->job_file, e) < 0 ||
                   hash_at(d, root, out, e) < 0 ||
                   string_at(d, root, "image", out->image, sizeof out->image, e) < 0 ||
                   string_at(d, root, "host", out->host, sizeof out->host, e) < 0 ||
                   string_at(d, root, "cpu_model", out->cpu_model, sizeof out->cpu_model, e) < 0 ||
                   count_at(d, root, "processes", &out->processes, e) < 0 ||
                   count_at(d, root, "parts", &out->parts, e) < 0 ||
                   count_at(d, root, "nonfinite_dropped", &out->nonfinite, e) < 0 || /* before issue 26 */
                   count_at(d, root, "nonfinite_samples", &out->nonfinite, e) < 0 ||
                   count_at(d, samples, "total", &out->samples_total, e) < 0 ||
                   number_at(d, samples, "per_pixel_mean", &out->spp_mean, e) < 0 ||
                   count_at(d, samples, "per_pixel_min", &out->spp_min, e) < 0 ||
                   count_at(d, samples, "per_pixel_max", &out->spp_max, e) < 0 ||
                   number_at(d, time, "wall_s", &out->wall_s, e) < 0 ||
                   number_at(d, time, "cpu_s", &out->cpu_s, e) < 0 ||
                   number_at(d, time, "sampler_s", &out->sampler_s, e) < 0 ||
                   number_at(d, time, "sampling_share", &out->sampling_share, e) < 0 ||
                   number_at(d, time, "ns_per_sample", &out->ns_per_sample, e) < 0 ||
                   number_at(d, error, "mse", &out->mse, e) < 0 ||
                   number_at(d, error, "rmse", &out->rmse, e) < 0 ||
                   number_at(d, error, "relmse", &out->relmse, e) < 0 ||
                   number_at(d, error, "relmse_robust", &out->relmse_robust, e) < 0 ||
                   string_at(d, error, "domain", out->error_domain, sizeof out->error_domain, e) < 0 ||
                   string_at(d, error, "reference", out->reference, sizeof out->reference, e) < 0 ||
                   number_at(d, error, "psnr", &out->psnr, e) < 0
               ? -1
               : 0;
}

int sidecar_read(const char *path, struct sidecar_info *out, struct err *e)
{
    uint8_t *data = NULL;
    size_t len = 0;
    struct ydoc d;
    memset(out, 0, sizeof *out);
    if (fileio_read_all(path, SIDECAR_MAX_BYTES, &data, &len, e) < 0)
        return -1;
    int rc = ydoc_parse(&d, path, data, len, e);
    free(data);
    if (rc == 0)
        rc = fill(&d, out, e);
    ydoc_free(&d);
    return rc;
}

int sidecar_matches(const char *path, uint64_t hash)
{
    struct sidecar_info info;
    struct err e;
    return sidecar_read(path, &info, &e) == 0 && info.has_hash && info.job_hash == hash;
}
