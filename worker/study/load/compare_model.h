/* compare_model: what a compare job is, once loaded (compare_load.h): its scenes with their
   references, variants, sweep points, seeds and every combination as an ordinary job; the figures
   its renders measured (run/), its verdict (judge/) and the machine it ran on, filled in as it goes;
   and a suite of such studies. The bottom of worker/study/: the loader, the judge, the
   presentation and the runner all read it. */
#ifndef COMPARE_MODEL_H
#define COMPARE_MODEL_H

#include <stdint.h>

#include "image/metrics.h"
#include "job/job.h"
#include "job/sidecar.h"
#include "study_env.h"
#include "study_inputs.h"
#include "verdict_model.h"

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
    struct img_mask *mask; /* `mask:`: the pixels every figure counts (owned); NULL: all */
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
    double flip;                          /* mean FLIP (HDR on linear, LDR on 8-bit) against it */
    struct sidecar_work work;             /* its render's work counts (the sidecar's "work") */
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
    /* The cost design's figures (study/run/compare_cost.h): per (scene, variant, point, block) the
       CPU seconds one image of the point costs, timed in block b; n_blocks 0 when not measured
       (the verdict then falls back on the images' own times, seed k as block k). */
    int n_blocks;
    double *cost_s; /* index compare_cost_index */
};

/* Index of a cost figure in c->cost_s. */
static inline int compare_cost_index(const struct compare *c, int scene, int variant, int point, int block)
{
    return ((scene * c->n_variants + variant) * c->n_points + point) * c->n_blocks + block;
}

/* Index of an item in c->items. */
static inline int compare_index(const struct compare *c, int scene, int variant, int point, int seed)
{
    return ((scene * c->n_variants + variant) * c->n_points + point) * c->n_seeds + seed;
}

/* Free c and all it holds (its inputs unless a suite's). NULL is fine. */
void compare_free(struct compare *c);

/* Most studies one suite may list, and most images all its studies may expand to together. */
#define COMPARE_SUITE_MAX_STUDIES 16
#define COMPARE_SUITE_MAX_ITEMS (4 * COMPARE_MAX_ITEMS)

struct compare_suite {
    char path[JOB_PATH_MAX];
    char name[JOB_NAME_MAX];
    int n_studies, n_items;
    struct compare *studies[COMPARE_SUITE_MAX_STUDIES]; /* owned, in the order listed */
    struct study_inputs *inputs; /* owned: the scenes and references of all studies, each read once */
};

/* Free s, its studies and their shared inputs. NULL is fine. */
void compare_suite_free(struct compare_suite *s);

#endif
