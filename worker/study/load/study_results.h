/* study_results: what a study's renders measured, the second of its three shapes (the plan,
   compare_model.h, is load/'s; the verdict, verdict_model.h, judge/'s): one row per image, the
   figures summary.csv serialises, and the cost design's timings. run/ appends it (a render, or the
   summary.csv of a finished folder read back); judge/ and present/ only read it. */
#ifndef STUDY_RESULTS_H
#define STUDY_RESULTS_H

#include <stdint.h>

#include "image/metrics.h"
#include "job/sidecar.h"
#include "study_inputs.h"

/* The figures a render can give (a row read back outside them is no figure): samples per pixel up
   to a job's most camera samples on one pixel (job_limits.h's LIMITS_MAX_JOB_SAMPLES), seconds up to
   about 30 years. */
#define STUDY_RESULTS_SPP_MAX 1e11
#define STUDY_RESULTS_SECONDS_MAX 1e9

/* One image's figures (one summary.csv row, less the settings its plan item holds). */
struct study_result {
    int done, has_error;
    int skipped; /* its image and sidecar were current (same hash): not rendered again */
    double spp_mean, wall_s, cpu_s, sampler_share;
    uint64_t nonfinite;           /* samples dropped as NaN or infinite */
    struct metrics error;         /* in the scene's reference's domain (linear unless a PNG/PPM) */
    struct metrics display_error; /* on the PNG's 8-bit display values, for comparison */
    double error_lowfreq;         /* errspec_lowfreq against the reference (NaN: not measurable) */
    double flip;                  /* mean FLIP (HDR on linear, LDR on 8-bit) against it */
    struct sidecar_work work;     /* its render's work counts (the sidecar's "work") */
    uint64_t hash;                /* the resume hash it was rendered under (not a column) */
};

/* The reference a scene's images were scored against, as run/ prepared or found it (the plan says
   which one is asked for: its kind, settings job or given image). */
struct study_ref_result {
    const struct study_ref *ref;  /* its pixels (kept in the plan's inputs); NULL before or without */
    char path[JOB_PATH_MAX];      /* its image once known (the given one, the cache's mean, or found) */
    struct study_ref_figures fig; /* over the scene's mask */
};

struct study_results {
    struct study_result *rows;     /* one per item of the plan, at its index (compare_index) */
    struct study_ref_result *refs; /* one per scene of the plan */
    /* The cost design's figures (study/run/compare_cost.h): per (scene, variant, point, block) the
       CPU seconds one image of the point costs, timed in block b; n_blocks 0 when not measured
       (the verdict then falls back on the images' own times, seed k as block k). */
    int n_blocks;
    double *cost_s; /* index compare_cost_index */
};

/* Rows for n images, each not done, and n_scenes references, none known (NAN figures); 0, or -1
   when out of memory. */
int study_results_init(struct study_results *r, int n, int n_scenes);

/* Free what r holds (r emptied; an empty one is fine). */
void study_results_free(struct study_results *r);

#endif
