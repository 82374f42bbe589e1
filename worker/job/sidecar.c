/* sidecar: job, sampler settings, sample counts, rays, times and error as JSON (SPEC "Stats sidecar"). */
#include "sidecar.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fileio.h"
#include "base/json.h"

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
    json_uint(&js, "width", (uint64_t)s->width);
    json_uint(&js, "height", (uint64_t)s->height);
    json_begin_array(&js, "size");
    json_uint(&js, NULL, (uint64_t)s->width);
    json_uint(&js, NULL, (uint64_t)s->height);
    json_end_array(&js);
    json_string(&js, "sampler", sampler_kind_name(j->sampler));
    json_number(&js, "threshold", j->threshold);
    json_string(&js, "light_sampler", sampler_kind_name(j->light_sampler));
    json_number(&js, "light_threshold", j->light_threshold);
    json_bool(&js, "light_sampling", j->light_sampling);
    json_string(&js, "integrator", j->nee ? "nee" : "mixture");
    json_string(&js, "sampler_dims", j->dims_all ? "all" : "pixel_light");
    json_uint(&js, "poisson_pool", (uint64_t)j->poisson_pool);
    json_uint(&js, "max_depth", (uint64_t)j->max_depth);
    json_uint(&js, "seed", j->seed);
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
    json_uint(&js, "nonfinite_dropped", t->nonfinite);
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
    if (js.oom) {
        json_free(&js);
        return NULL;
    }
    return js.buf;
}

int sidecar_matches(const char *path, uint64_t hash)
{
    uint8_t *data;
    size_t len;
    struct err e;
    if (fileio_read_all(path, 1u << 20, &data, &len, &e) < 0)
        return 0;
    char want[64];
    snprintf(want, sizeof want, SIDECAR_HASH_KEY "%016" PRIx64 "\"", hash);
    int ok = strstr((const char *)data, want) != NULL;
    free(data);
    return ok;
}
