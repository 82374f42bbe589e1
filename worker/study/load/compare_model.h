/* compare_model: what a compare job is, once loaded (compare_load.h): its scenes with the
   reference each asks for, variants, sweep points, seeds and every combination as an ordinary job,
   the plan, the first of a study's three shapes, fixed after load. Beside it the handle keeps the
   other two: `results` (study_results.h), written by run/'s functions that take the plan const and
   the results apart (compare_run_item(c, &c->results, ...)), and `verdict`, judge/'s output from
   both (verdict_from.h) with the machine it ran on. And a suite of such studies. The bottom of
   worker/study/: the loader, the judge, the presentation and the runner all read it. */
#ifndef COMPARE_MODEL_H
#define COMPARE_MODEL_H

#include <stdint.h>

#include "job/job.h"
#include "study_env.h"
#include "study_inputs.h"
#include "study_results.h"
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
    const struct study_ref *image;   /* _IMAGE: the given reference image, read at load; else NULL */
    int width, height;               /* of every image of this scene */
    int ref_kind;                    /* COMPARE_REF_NONE | _SETTINGS | _IMAGE */
    struct job ref_job;              /* _SETTINGS: the reference render (output set at run time) */
    enum img_domain ref_domain;      /* linear (a settings reference: the cache's EXR; a given EXR or
                                        PFM) or 8-bit display values (a given PNG or PPM) */
    struct img_mask *mask;           /* `mask:`: the pixels every figure counts (owned); NULL: all */
};

enum { COMPARE_REF_NONE, COMPARE_REF_SETTINGS, COMPARE_REF_IMAGE };

/* One combination: an ordinary job and its indices (what it measured: c->results.rows, same index). */
struct compare_item {
    struct job job;
    int scene, variant, point, seed; /* indices */
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
    struct study_inputs *inputs;  /* its scenes and references, each read once (a suite's shared) */
    int owns_inputs;              /* compare_free frees inputs (not a suite's) */
    enum verdict_rank_by rank_by; /* `rank_by:` (default mean): the centre over seeds of relMSE */
    /* run/'s: a row per item, a reference per scene (allocated at load, nothing done or known) */
    struct study_results results;
    /* judge/'s output, kept for presenting: set by compare_write_outputs from verdict_from_compare */
    struct verdict_study verdict;
    struct study_env env; /* the command, program, compiler, CPU and load, at that time */
    int has_verdict;
};

/* Index of a cost figure in c->results.cost_s. */
static inline int compare_cost_index(const struct compare *c, int scene, int variant, int point, int block)
{
    return ((scene * c->n_variants + variant) * c->n_points + point) * c->results.n_blocks + block;
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
