/* verdict_from: a compare job's figures, per scene, handed to verdict_scene_compute. */
#include "verdict_from.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "compare_stats.h"
#include "image/imgio.h"

/* The arrays of one scene's figures, freed together. */
struct figures_mem {
    struct verdict_figures f;
    const char **names; /* n_variants variants, n_variants samplers, n_points points */
    int *pools;
    uint64_t *nonfinite;
    double *d; /* every array of doubles */
};

static void mem_free(struct figures_mem *m)
{
    free(m->names), free(m->pools), free(m->nonfinite), free(m->d);
}

static int gather(const struct compare *c, int s, const char *dir, const struct rgbf *ref,
                  struct figures_mem *m)
{
    size_t nv = (size_t)c->n_variants, per = nv * c->n_points, n = per * c->n_seeds;
    /* no cost design: the images' own times */
    int blocks = c->results.n_blocks > 1 ? c->results.n_blocks : c->n_seeds;
    m->names = calloc(2 * nv + c->n_points, sizeof *m->names);
    m->pools = calloc(nv, sizeof *m->pools);
    m->nonfinite = calloc(n, sizeof *m->nonfinite);
    m->d = calloc(6 * n + 4 * per + n * VERDICT_SPEC_RINGS + per * blocks, sizeof *m->d);
    if (!m->names || !m->pools || !m->nonfinite || !m->d)
        return -1;
    const char **variants = m->names, **samplers = variants + nv, **points = samplers + nv;
    double *spp = m->d, *cpu = spp + n, *rel = cpu + n, *share = rel + n, *radiance = share + n;
    double *lowfreq = radiance + n, *rel_of_mean = lowfreq + n, *bias_rel = rel_of_mean + per;
    double *peak_p = bias_rel + per, *aniso = peak_p + per, *spec_ring = aniso + per;
    double *cost = spec_ring + n * VERDICT_SPEC_RINGS;
    struct verdict_figures *f = &m->f;
    *f = (struct verdict_figures){.study = c->name,
                                  .scene = c->scenes[s].name,
                                  .n_variants = c->n_variants,
                                  .n_points = c->n_points,
                                  .n_seeds = c->n_seeds,
                                  .variants = variants,
                                  .samplers = samplers,
                                  .pools = m->pools,
                                  .points = points,
                                  .spp = spp,
                                  .cpu_s = cpu,
                                  .relmse = rel,
                                  .sampler_share = share,
                                  .nonfinite = m->nonfinite,
                                  .rel_of_mean = rel_of_mean,
                                  .bias_rel = bias_rel,
                                  .radiance = radiance,
                                  .lowfreq = lowfreq,
                                  .spec_ring = spec_ring,
                                  .spec_peak_p = peak_p,
                                  .spec_aniso = aniso,
                                  .n_blocks = blocks,
                                  .cost_s = cost,
                                  .cost_from_images = c->results.n_blocks < 2,
                                  .rank_by = c->rank_by,
                                  .ref = c->results.refs[s].fig};
    if (ref && !(f->ref.radiance > 0))
        f->ref.radiance =
            compare_stats_mean_radiance(ref, c->scenes[s].mask); /* an image reference: its noise unknown */
    for (int p = 0; p < c->n_points; p++)
        points[p] = c->points[p];
    for (int v = 0; v < c->n_variants; v++) {
        const struct job *j = &c->items[compare_index(c, s, v, 0, 0)].job;
        variants[v] = c->variants[v];
        samplers[v] = sampler_kind_name(j->spec.pixel.kind);
        m->pools[v] = j->spec.poisson_pool;
        for (int p = 0; p < c->n_points; p++) {
            struct compare_seed_stats st = {.radiance = radiance + verdict_at(f, v, p, 0),
                                            .spec_ring = spec_ring +
                                                         (size_t)verdict_at(f, v, p, 0) * VERDICT_SPEC_RINGS};
            struct err ignored;
            int vp = v * c->n_points + p;
            rel_of_mean[vp] = bias_rel[vp] = peak_p[vp] = aniso[vp] = NAN;
            for (int k = 0; k < c->n_seeds; k++)
                st.radiance[k] = NAN;
            for (int r = 0; r < c->n_seeds * VERDICT_SPEC_RINGS; r++)
                st.spec_ring[r] = NAN;
            if (ref && compare_stats_seed_images(c, s, v, p, dir, ref, &st, &ignored) == 0)
                rel_of_mean[vp] = st.rel_of_mean, bias_rel[vp] = st.bias_rel, peak_p[vp] = st.peak_p,
                aniso[vp] = st.anisotropy;
            else
                f->images_unread += ref != NULL;
            for (int b = 0; b < blocks; b++)
                cost[verdict_cost_at(f, v, p, b)] = c->results.n_blocks > 1
                                                        ? c->results.cost_s[compare_cost_index(c, s, v, p, b)]
                                                        : c->results.rows[compare_index(c, s, v, p, b)].cpu_s;
            for (int k = 0; k < c->n_seeds; k++) {
                const struct study_result *r = &c->results.rows[compare_index(c, s, v, p, k)];
                int i = verdict_at(f, v, p, k);
                spp[i] = r->spp_mean, cpu[i] = r->cpu_s, share[i] = r->sampler_share;
                rel[i] = r->has_error ? r->error.relmse : NAN;
                lowfreq[i] = r->has_error ? r->error_lowfreq : NAN;
                m->nonfinite[i] = r->nonfinite;
            }
        }
    }
    return 0;
}

/* Add text to v's warnings. 0 or -1. */
static int add_warning(struct verdict_scene *v, const char *text)
{
    char(*w)[VERDICT_TEXT_MAX] = realloc(v->warnings, (size_t)(v->n_warnings + 1) * sizeof *w);
    if (!w)
        return -1;
    v->warnings = w;
    snprintf(w[v->n_warnings++], VERDICT_TEXT_MAX, "%s", text);
    return 0;
}

/* A warning of n images (text: a format of n and its plural's "s") when there are any and room. */
static void say_images(struct verdict_scene *vs, const char *text, int n)
{
    if (n && vs->n_warnings < VERDICT_SAY_MAX)
        snprintf(vs->warnings[vs->n_warnings++], VERDICT_TEXT_MAX, text, n, sbuf_plural(n));
}

/* What the runner found, said: a folder's missing parts per scene; several CPU models listed, and a
   warning on each scene's equal CPU time. 0 or -1 (no memory). */
static int say_found(const struct verdict_found *f, struct verdict_study *out)
{
    char text[VERDICT_TEXT_MAX];
    snprintf(text, sizeof text,
             "left out: %%d image%%s whose samples_per_pixel_mean, wall_s, cpu_s or sampler_share in "
             "summary.csv is not a figure (spp in [0, %g], seconds in [0, %g], share in [0, 1])",
             STUDY_RESULTS_SPP_MAX, STUDY_RESULTS_SECONDS_MAX);
    for (int s = 0; f && s < out->n_scenes; s++) {
        struct verdict_scene *vs = &out->scenes[s];
        say_images(vs,
                   "skipped: non-finite samples and what needs each variant's sampler (%d sidecar%s missing)",
                   f->no_sidecar ? f->no_sidecar[s] : 0);
        say_images(vs, "left out: %d image%s whose relmse in summary.csv is not an error (not a number >= 0)",
                   f->no_relmse ? f->no_relmse[s] : 0);
        say_images(vs, text, f->no_figures ? f->no_figures[s] : 0);
    }
    if (!f || f->n_machines < 2)
        return 0;
    snprintf(out->machines, sizeof out->machines, "%s", f->machines);
    snprintf(
        text, sizeof text,
        "the images were rendered on %d%s CPU models: their own CPU seconds (summary.csv) do not compare; "
        "equal CPU time is ranked by the cost design, timed on the one machine that gathered the study",
        f->n_machines, f->more_machines ? "+" : "");
    for (int s = 0; s < out->n_scenes; s++)
        if (add_warning(&out->scenes[s], text) < 0)
            return -1;
    return 0;
}

int verdict_from_compare(const struct compare *c, const char *dir, const struct verdict_found *found,
                         struct verdict_study *out, struct err *e)
{
    *out = (struct verdict_study){.n_scenes = c->n_scenes};
    snprintf(out->name, sizeof out->name, "%s", c->name);
    out->scenes = calloc((size_t)c->n_scenes, sizeof *out->scenes);
    if (!out->scenes)
        return err_set(e, NULL, 0, 0, "out of memory");
    for (int s = 0; s < c->n_scenes; s++) {
        const struct compare_scene *cs = &c->scenes[s];
        const struct study_ref_result *rr = &c->results.refs[s];
        struct rgbf read = {0};
        struct figures_mem m = {0};
        struct err unread;
        /* the pixels the study scored against (rr->ref); a study judged again from its outputs reads
           the file; without them the checks on images are skipped (the verdict says so) */
        const struct rgbf *ref = cs->ref_kind == COMPARE_REF_NONE                    ? NULL
                                 : rr->ref                                           ? &rr->ref->f
                                 : imgio_read_f(rr->path, &read, NULL, &unread) == 0 ? &read
                                                                                     : NULL;
        int rc = gather(c, s, dir, ref, &m) < 0 ? err_set(e, NULL, 0, 0, "out of memory") : 0;
        if (rc == 0) {
            m.f.reference_unread = cs->ref_kind != COMPARE_REF_NONE && !ref;
            rc = verdict_scene_compute(&m.f, &out->scenes[s], e);
        }
        mem_free(&m);
        image_f_free(&read);
        if (rc < 0) {
            verdict_study_free(out);
            return -1;
        }
    }
    if (say_found(found, out) < 0) {
        verdict_study_free(out);
        return err_set(e, NULL, 0, 0, "out of memory");
    }
    return 0;
}
