/* compare: compare jobs: scenes x variants x sweep x seeds, each an ordinary render scored
   against a cached per-scene reference, summarised as CSV, SVG and HTML. */
#ifndef COMPARE_H
#define COMPARE_H

#include <stdint.h>

#include "job/job.h"
#include "image/metrics.h"
#include "job/run.h"
#include "study/load/study_env.h"
#include "study/load/study_inputs.h"
#include "study/judge/verdict.h"

/* Most images one compare job may expand to. */
#define COMPARE_MAX_ITEMS 4096
#define COMPARE_LABEL_MAX 64
/* The reference's seed unless its settings give one: apart from the study's seeds, so the
   reference's noise is independent of every image scored against it. */
#define COMPARE_REF_SEED 1000003

struct compare_scene {
    char name[COMPARE_LABEL_MAX];    /* the scene file's stem: "checker" */
    const struct study_scene *input; /* its file, read and parsed once (c->inputs holds it) */
    const struct study_ref *ref;     /* its reference's pixels, read once: an image at load, settings
                                        when prepared (compare_ref_prepare); NULL before or without */
    int width, height;               /* of every image of this scene */
    int ref_kind;                    /* COMPARE_REF_NONE | _SETTINGS | _IMAGE */
    struct job ref_job;              /* _SETTINGS: the reference render (output set at run time) */
    char ref_path[JOB_PATH_MAX];     /* the reference image once known (cache or given path) */
    enum img_domain ref_domain;      /* linear (a float image: the cache's EXR, a given EXR or PFM) or
                                        8-bit display values (a given PNG or PPM) */
    int ref_reused;                  /* the cached reference was reused */
    double ref_wall_s;               /* seconds its render took (now or when it was cached) */
    double ref_spp;                  /* its samples per pixel (from its render or sidecar), 0 unknown */
    /* A settings reference is the mean of two independent halves (compare_ref.c); from their
       difference: its own relMSE, its mean radiance and that mean's standard error. NAN: unknown
       (an image reference: its mean radiance is read at the verdict, its noise is not known). */
    double ref_relmse, ref_radiance, ref_radiance_se;
};

enum { COMPARE_REF_NONE, COMPARE_REF_SETTINGS, COMPARE_REF_IMAGE };

/* One combination: an ordinary job plus what its render measured. */
struct compare_item {
    struct job job;
    int scene, variant, point, seed; /* indices */
    int done, has_error;
    int skipped; /* its image and sidecar were current (same hash): not rendered again */
    double spp_mean, wall_s, cpu_s, sampler_share;
    uint64_t spp_min, spp_max, nonfinite; /* nonfinite: samples dropped as NaN or infinite */
    struct metrics error;                 /* in the scene's reference's domain (linear unless a PNG/PPM) */
    struct metrics display_error;         /* on the PNG's 8-bit display values, for comparison */
    double error_lowfreq;                 /* errspec_lowfreq against the reference (NaN: not measurable) */
};

struct compare {
    char path[JOB_PATH_MAX];
    char name[JOB_NAME_MAX];
    int n_scenes, n_variants, n_points, n_seeds, n_items;
    struct compare_scene *scenes;
    char (*variants)[COMPARE_LABEL_MAX];    /* labels */
    char (*points)[COMPARE_LABEL_MAX];      /* sweep point labels: "threshold 5" */
    char sweep_keys[COMPARE_LABEL_MAX * 2]; /* "threshold" or "threshold, light_threshold"; "" */
    uint64_t *seeds;
    struct compare_item *items;   /* index compare_index(c, scene, variant, point, seed) */
    struct verdict_study verdict; /* filled by compare_run once every image is scored */
    struct study_env env;         /* the command, program, compiler, CPU and load, at that time */
    int has_verdict;
    struct study_inputs *inputs; /* its scenes and references, each read once (a suite's shared) */
    int owns_inputs;             /* compare_free frees inputs (not a suite's) */
};

/* Load, validate and expand the compare job at path into a new struct compare. Everything a
   render needs is checked here (keys, values, scenes, reference images, set sizes), so a bad
   job fails before anything renders. NULL with e = "file:line:col: key: message". */
struct compare *compare_load(const char *path, struct err *e);

/* compare_load of the job file at path already parsed into d (jobfile_open), which is read, not
   kept. */
struct compare *compare_load_doc(const struct ydoc *d, const char *path, struct err *e);

/* compare_load_doc reading its scenes and references through in (a suite's, shared by its
   studies, which outlives the result): a file another study read is not read again. */
struct compare *compare_load_in(const struct ydoc *d, const char *path, struct study_inputs *in,
                                struct err *e);
void compare_free(struct compare *c);

/* Index of an item in c->items. */
static inline int compare_index(const struct compare *c, int scene, int variant, int point, int seed)
{
    return ((scene * c->n_variants + variant) * c->n_points + point) * c->n_seeds + seed;
}

/* Render every reference (or reuse the cache under OUT/.cache/) and every combination, then
   write summary.csv, chart.svg and report.html under OUT/<name>/. Every render keeps its float
   image (<stem>.exr) beside its PNG; errors are measured on those linear values. Returns 0, 1 when a render
   or write failed, 2 on bad input found late (a reference image); e says why. Prints one
   progress line per combination when o->progress and not o->quiet. */
int compare_run(struct compare *c, const struct run_opts *o, struct err *e);

/* Render combination i alone (the queue's fan-out: one render per queue entry), its scene's
   reference prepared first (reused from the cache when there). 0, 1 or 2 as compare_run. */
int compare_run_item(struct compare *c, int i, const struct run_opts *o, struct err *e);

/* From a finished study (every item's figures filled, its images and float copies in dir, each
   settings reference's ref_path and noise known: compare_ref_prepare or compare_ref_measure): the
   verdict (verdict_from_compare, into c->verdict), then summary.csv, chart.svg (report_chart_svg),
   verdict.json (verdict_json_text) and report.html (report_html) under dir's lock. The gather of a
   study spread over a queue calls this as compare_run does. 0, or -1 with e filled. */
int compare_write_outputs(struct compare *c, const char *dir, const struct run_opts *o, struct err *e);

/* The line that ends a compare job's run: its images, references, time, output folder and the
   verdict at equal CPU time ("compare: 120 images (2 scenes x ...), references: 1 rendered, ...,
   41 s -> out/compare/; at equal CPU time: ..."). */
void compare_summary_line(const struct compare *c, double wall_s, const char *out_dir, char *buf, size_t n);

#endif
