/* verdict: what a compare job's figures conclude, per study and scene: the ranking at equal
   samples, at equal CPU time and by slope, with ties where variants differ by less than their
   seeds' spread; the failure modes found; guards; and plain sentences. Pure arithmetic on the
   figures (verdict_from.c gathers them from a finished compare job), so the rules are testable on
   constructed figures. */
#ifndef VERDICT_H
#define VERDICT_H

#include <stddef.h>
#include <stdint.h>

#include "base/err.h"
#include "base/json.h"
#include "base/sbuf.h"

/* A share of the error that repeats in every seed above this is structured (aliasing, a pattern,
   a bias): pure noise averages away across seeds. */
#define VERDICT_STRUCTURED_SHARE 0.5
/* A variant whose seeds' mean radiance is more standard errors than this off the reference's (the
   seeds' spread and the reference's noise together) is biased. */
#define VERDICT_BIAS_SE 4
/* The bias check needs this many seeds: with fewer, their spread is itself too uncertain (4
   standard errors from 2 seeds happen by chance 16% of the time, from 8 seeds 0.5%). */
#define VERDICT_BIAS_SEEDS 4
/* A point's relMSE within this factor of the reference's own is dominated by the reference's
   noise: warned. */
#define VERDICT_REF_NOISE 2
/* A sweep "changes the samples" when its points' mean samples per pixel span more than this ratio:
   a light_threshold, max_depth or poisson_pool sweep does not, though a poisson pixel sampler's
   counts move by a hair from point to point. */
#define VERDICT_SAMPLES_VARY 1.05
/* Error "stops falling" at a step whose local slope of log relMSE against log samples is above
   this (noise alone falls as spp^-1). */
#define VERDICT_STALL_SLOPE (-0.3)
/* A sampler's share of its render's CPU time above this is a failure: drawing the points costs
   more than tracing them. */
#define VERDICT_SAMPLER_SHARE 0.5
/* A reference with fewer than this many times the densest point's samples per pixel is too noisy
   to rank the densest points by. */
#define VERDICT_REF_FACTOR 4
#define VERDICT_LABEL_MAX 64
/* Room for warnings and sentences per scene (verdict_scene's arrays); more are left out. */
#define VERDICT_SAY_MAX 16
#define VERDICT_TEXT_MAX 400

/* One scene of one study, every (variant, point, seed) at verdict_at(). Arrays are the caller's. */
struct verdict_figures {
    const char *study, *scene;
    int n_variants, n_points, n_seeds;
    const char *const *variants; /* labels */
    const char *const *samplers; /* per variant: its pixel sampler's name ("poisson") */
    const int *pools;            /* per variant: poisson_pool (0: fresh sets) */
    const char *const *points;   /* sweep point labels ("threshold 5") */
    const double *spp;           /* samples per pixel (mean over the image) */
    const double *cpu_s;         /* the render's CPU seconds */
    const double *relmse;        /* against the reference; NAN when not measured */
    const double *sampler_share; /* fraction of CPU time drawing point sets */
    const uint64_t *nonfinite;   /* samples dropped as NaN or infinite */
    const double *rel_of_mean;   /* per (variant, point): relMSE of the seeds' mean image; NAN unknown */
    const double *bias_rel;      /* per (variant, point): the relMSE the mean image's offset in mean
                                    radiance alone gives (the reference scaled by it); NAN unknown */
    const double *radiance;      /* per (variant, point, seed): the image's mean radiance; NAN unknown */
    const double *lowfreq;       /* per (variant, point, seed): error_lowfreq (errspec.h); NAN unknown;
                                    NULL: none measured */
    double ref_spp;              /* the reference's samples per pixel, 0 when unknown */
    double ref_relmse;           /* the reference's own relMSE (from its halves), NAN unknown */
    double ref_radiance;         /* the reference's mean radiance, NAN unknown */
    double ref_radiance_se;      /* its standard error (from its halves), NAN unknown */
    int reference_unread;        /* the reference's pixels could not be read: no checks on images */
    int images_unread;           /* (variant, point)s whose seed images could not be read */
};

static inline int verdict_at(const struct verdict_figures *f, int v, int p, int k)
{
    return (v * f->n_points + p) * f->n_seeds + k;
}

enum verdict_status { VERDICT_CLEAR, VERDICT_TIE, VERDICT_INCONCLUSIVE };

/* One variant in a ranking (verdict_rank.h fills it): its figure over the seeds. */
struct verdict_entry {
    int variant;
    double value, lo, hi; /* relMSE: the geometric mean over seeds, else the mean; the seeds' min, max */
    double mean, se;      /* the ranked figure (log relMSE, or the slope): mean and standard error */
    double m2;            /* sum of squared deviations from mean (while adding seeds) */
    int n;                /* seeds measured */
    int rank;             /* 1 + the number of variants that beat it (verdict_beats) */
    int unreached;        /* its cheapest point costs far more than the common point: it cannot be had
                             there (value, lo, hi: its cheapest point's) */
};

/* Best first. status: CLEAR when one variant alone has rank 1, TIE when several share it but some
   variant is beaten, INCONCLUSIVE when none beats another (or there is one seed: no spread). */
struct verdict_ranking {
    double at;     /* the common samples per pixel or CPU seconds ranked at; NAN for slopes */
    int log_scale; /* values compared as logarithms (relMSE: a ratio); slopes as they are */
    enum verdict_status status;
    double p_cut; /* the largest Welch p-value Holm's procedure rejects: pairs at or below it are
                     separated; -1 when none is */
    int n;
    struct verdict_entry *e;
};

enum verdict_failure_kind {
    VERDICT_STRUCTURED,
    VERDICT_STALLS,
    VERDICT_NONFINITE,
    VERDICT_SHARE,
    VERDICT_BIASED
};
#define VERDICT_FAILURE_KINDS 5

struct verdict_failure {
    enum verdict_failure_kind kind;
    int variant, point; /* point: where it shows most (-1: throughout) */
    double value;       /* the repeated share, the local slope, the samples dropped, the CPU share, the
                           bias in percent of the reference's mean radiance */
    double detail;      /* structured: the share of the error that is bias; biased: standard errors */
    char text[VERDICT_TEXT_MAX];
};

/* How the error looks (verdict_look.h): error_lowfreq, the error's low-frequency energy share over
   white noise's (1: white, below 1: bluer), per variant at the sparsest samples per pixel that every
   variant has, where the look shows most. */
struct verdict_look {
    double at;                        /* that samples per pixel (mean); NAN without points */
    int *point;                       /* per variant: its point nearest `at` (in log spp) */
    double *mean, *se;                /* per (variant, point): error_lowfreq's mean over seeds, its SE */
    double *rel;                      /* per (variant, point): relMSE's geometric mean over seeds */
    struct verdict_ranking by_relmse; /* at `point`: log relMSE, as by_samples ranks it */
    struct verdict_ranking by_look;   /* the variants by_relmse ranks first (equal relMSE): mean
                                         error_lowfreq, lowest (bluest) first; n 0 when unmeasured */
};

struct verdict_scene {
    char study[VERDICT_LABEL_MAX], scene[VERDICT_LABEL_MAX];
    int n_variants, n_points, n_seeds;
    double ref_relmse;   /* the reference's own relMSE, subtracted from every relMSE ranked; NAN unknown */
    double *repeat;      /* per (variant, point): the share of the error repeating in every seed, NAN */
    double *repeat_bias; /* per (variant, point): the part of that share a bias in mean radiance makes */
    int *samples_vary;   /* per variant: verdict_samples_vary over its points */
    char (*variants)[VERDICT_LABEL_MAX];
    struct verdict_ranking by_samples, by_cpu, by_slope;
    struct verdict_look look;
    int n_failures, n_warnings, n_sentences;
    struct verdict_failure *failures;
    char (*warnings)[VERDICT_TEXT_MAX];
    char (*sentences)[VERDICT_TEXT_MAX];
};

/* One study: its scenes' verdicts. */
struct verdict_study {
    char name[VERDICT_LABEL_MAX];
    int n_scenes;
    struct verdict_scene *scenes;
    char machines[VERDICT_TEXT_MAX]; /* the CPU models its images were rendered on, "; "-joined, when
                                        more than one (study_machines.h): equal CPU time mixes them */
};

/* Whether a sweep whose points' mean samples per pixel run from lo to hi changes the samples (by
   more than VERDICT_SAMPLES_VARY): a slope and "stops falling" need it to. */
int verdict_samples_vary(double lo, double hi);

/* The verdict of one scene from its figures. 0, or -1 with e filled (out of memory). */
int verdict_scene_compute(const struct verdict_figures *f, struct verdict_scene *out, struct err *e);
void verdict_scene_free(struct verdict_scene *v);
void verdict_study_free(struct verdict_study *s);

/* The winner at equal CPU time, for people: "sobol", "jitter = sobol (tie)", "inconclusive". */
void verdict_winner(const struct verdict_scene *v, char *buf, size_t n);

#endif
