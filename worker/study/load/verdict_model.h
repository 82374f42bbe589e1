/* verdict_model: what a verdict holds (verdict.h computes it, verdict_out.h presents it): per
   scene of a study, its rankings, failures, look, warnings and sentences. The model of a study
   (compare_model.h) keeps one; the rules that fill it are verdict.h's. */
#ifndef VERDICT_MODEL_H
#define VERDICT_MODEL_H

#define VERDICT_LABEL_MAX 64
/* Room for warnings and sentences per scene (verdict_scene's arrays); more are left out. */
#define VERDICT_SAY_MAX 16
#define VERDICT_TEXT_MAX 400

/* What a (variant, point)'s seeds are summed up by (`rank_by:`): the mean of their log relMSE (the
   geometric mean), or its median (steadier when a few seeds draw fireflies). */
enum verdict_rank_by { VERDICT_RANK_MEAN, VERDICT_RANK_MEDIAN };

enum verdict_status { VERDICT_CLEAR, VERDICT_TIE, VERDICT_INCONCLUSIVE };

/* One variant in a ranking (verdict_rank.h fills it): its figure over the seeds. */
struct verdict_entry {
    int variant;
    double value, lo,
        hi;           /* relMSE: the geometric mean over seeds, else the mean; its 95% confidence interval */
    double mean, se;  /* the ranked figure (log relMSE, or the slope): mean and standard error */
    double m2;        /* sum of squared deviations from mean (while adding seeds) */
    int n;            /* seeds measured */
    int rank;         /* 1 + the number of variants that beat it (verdict_beats) */
    int unreached;    /* its cheapest point costs far more than the common point: it cannot be had
                         there (value, lo, hi: its cheapest point's) */
    int extrapolated; /* equal CPU time: read off its error-against-time line beyond its points */
    int untold;       /* equal CPU time: the common time lies too far beyond its points (or it has
                         one point: no line): the study cannot tell, it is separated from none */
};

/* Best first. status: CLEAR when one variant alone has rank 1, TIE when several share it but some
   variant is beaten, INCONCLUSIVE when none beats another (or there is one seed: no spread). */
struct verdict_ranking {
    double at; /* the common samples per pixel or CPU seconds ranked at; NAN for slopes */
    enum verdict_status status;
    double p_cut;   /* the largest Welch p-value Holm's procedure rejects: pairs at or below it are
                       separated; -1 when none is */
    double *pair_p; /* optional, owned: per pair of variants (pair_n x pair_n, by variant index) the
                       two-sided p-value of a test of their own (equal CPU time); NULL: Welch's on
                       the entries */
    int pair_n;
    int n;
    struct verdict_entry *e;
};

enum verdict_failure_kind {
    VERDICT_STRUCTURED,
    VERDICT_STALLS,
    VERDICT_NONFINITE,
    VERDICT_SHARE,
    VERDICT_BIASED,
    VERDICT_HEAVY_TAILED,
    VERDICT_PATTERN
};
#define VERDICT_FAILURE_KINDS 7
/* The rings of a radially averaged error spectrum (errspec.h's ERRSPEC_RINGS). */
#define VERDICT_SPEC_RINGS 16

struct verdict_failure {
    enum verdict_failure_kind kind;
    int variant, point; /* point: where it shows most (-1: throughout) */
    double value;       /* the repeated share, the local slope, the samples dropped, the CPU share, the
                           bias in percent of the reference's mean radiance, the seeds' largest relMSE over
                           their smallest (heavy_tailed), the peak's chance bound (structured) */
    double detail;      /* structured: the share of the error that is bias; biased: standard errors;
                           heavy_tailed: the worst seed's share of the seeds' summed relMSE;
                           structured: the anisotropy */
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
    enum verdict_rank_by rank_by; /* the centre over seeds every relMSE figure uses */
    double ref_relmse;   /* the reference's own relMSE, subtracted from every relMSE ranked; NAN unknown */
    double *repeat;      /* per (variant, point): the share of the error repeating in every seed, NAN */
    double *repeat_bias; /* per (variant, point): the part of that share a bias in mean radiance makes */
    int *samples_vary;   /* per variant: verdict_samples_vary over its points */
    /* The one figure of a (variant, point) everywhere (chart, table, sentences, failures): per
       (variant, point) the geometric mean over seeds of relMSE with the reference's noise taken out,
       and its 95% confidence interval (Student's t on the mean log); NAN unknown. */
    double *point_rel, *point_rel_lo, *point_rel_hi;
    /* Per (variant, point): the CPU seconds one image costs, the cost design's geometric mean over
       blocks. */
    double *cost;
    /* The error's spectrum per (variant, point, ring): each ring's power over the mean power (white
       noise 1), the seeds' geometric mean and its +- one standard deviation band; per (variant,
       point): the seeds' pooled spectrum's peak chance bound and anisotropy (errspec.h). NAN: not
       measured. */
    double *spec, *spec_lo, *spec_hi, *spec_peak_p, *spec_aniso;
    int cost_from_images; /* no cost design measured (an older folder): each image's own time, seed k
                             as block k */
    char (*variants)[VERDICT_LABEL_MAX];
    struct verdict_ranking by_samples, by_cpu, by_slope;
    struct verdict_look look;
    int n_failures, n_warnings, n_sentences;
    struct verdict_failure *failures;
    char (*warnings)[VERDICT_TEXT_MAX];
    char (*sentences)[VERDICT_TEXT_MAX];
};

/* What the runner found beside a study's plan and results, for its verdict to say
   (verdict_from_compare): the CPU models its images were rendered on (study_machines.h: the first
   ones "; "-joined, how many are listed, whether there were more), and, reading a folder back
   (worker verdict), per scene how many images had no sidecar, a relmse that is no error, figures
   out of range (NULL: none). */
struct verdict_found {
    char machines[VERDICT_TEXT_MAX];
    int n_machines, more_machines;
    const int *no_sidecar, *no_relmse, *no_figures;
};

/* One study: its scenes' verdicts. */
struct verdict_study {
    char name[VERDICT_LABEL_MAX];
    int n_scenes;
    struct verdict_scene *scenes;
    char machines[VERDICT_TEXT_MAX]; /* the CPU models its images were rendered on, "; "-joined, when
                                        more than one (study_machines.h): equal CPU time mixes them */
};

/* Variant v's entry in r, or NULL when r does not rank it. */
const struct verdict_entry *verdict_entry_of(const struct verdict_ranking *r, int v);

/* Variant v's failure of that kind in s, or NULL (NULL too when s is). */
const struct verdict_failure *verdict_failure_of(const struct verdict_scene *s, int v,
                                                 enum verdict_failure_kind kind);

/* Free what a verdict's arrays hold (the struct emptied; each accepts an empty one). */
void verdict_look_free(struct verdict_look *l);
void verdict_scene_free(struct verdict_scene *v);
void verdict_study_free(struct verdict_study *s);

#endif
