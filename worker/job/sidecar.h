/* sidecar: the JSON stats file written beside every image, and read back. */
#ifndef SIDECAR_H
#define SIDECAR_H

#include "procs.h"
#include "job.h"
#include "image/metrics.h"

struct sidecar {
    const struct job *job;
    int width, height;
    const struct procs_result *res;
    const struct metrics *error;  /* NULL when the job has no reference */
    enum img_domain error_domain; /* what error was measured on: linear radiance or 8-bit values */
    const char *image;            /* the image file's name */
    int parts;                    /* > 0: merged from this many --part files (res->proc[i] = part i) */
};

/* Largest sidecar sidecar_read reads (one with PROCS_MAX_PROCESSES per_process entries is ~40 kB). */
#define SIDECAR_MAX_BYTES (1u << 20)

/* A render's work counts (the sidecar's "work"): deterministic, the same on every machine, run,
   process count and split. render_stats' counters, named as the sidecar names them. */
struct sidecar_work {
    uint64_t camera_samples, path_segments, shadow_rays; /* segments: camera rays included */
    uint64_t pixel_points, light_points, padded_points;  /* points taken from each kind of set */
    uint64_t pixel_sets, light_sets, padded_sets;        /* sets drawn of each kind */
};

/* The work counts of st. */
struct sidecar_work sidecar_work_of(const struct render_stats *st);

/* What callers read back from a sidecar (sidecar_read). A key the file lacks leaves its field ""
   or 0; a number written as null (not finite) reads as NaN. */
struct sidecar_info {
    char job[JOB_NAME_MAX];
    char job_file[JOB_PATH_MAX]; /* as written: a byte that was not UTF-8 became U+FFFD */
    int has_hash;                /* job_hash was there, 16 hex digits */
    uint64_t job_hash;
    char image[JOB_NAME_MAX];
    char host[128], cpu_model[128]; /* where it was rendered ("" in sidecars of earlier versions) */
    uint64_t processes, parts;
    uint64_t samples_total, spp_min, spp_max; /* samples.total, per_pixel_min, per_pixel_max */
    uint64_t nonfinite;                       /* nonfinite_samples (nonfinite_dropped before) */
    double spp_mean;                          /* samples.per_pixel_mean */
    double wall_s, cpu_s, sampler_s, sampling_share, ns_per_sample; /* time.* (the job's) */
    int has_error;                                                  /* error.* were there */
    char error_domain[16];        /* what the error was measured on: "linear" or "8-bit" */
    char reference[JOB_PATH_MAX]; /* error.reference: the reference image as the job named it */
    double mse, rmse, relmse, relmse_robust, psnr;
    struct render_spec spec; /* the render's settings (a setting absent: its default) */
    int has_work;            /* "work" was there (sidecars since issue 35) */
    struct sidecar_work work;
};

/* Render the sidecar as JSON text into a malloc'd string (caller frees); NULL on no memory. */
char *sidecar_json(const struct sidecar *s);

/* Read the sidecar at path (at most SIDECAR_MAX_BYTES; JSON, read as YAML) into out. 0, or -1 with
   e filled: unreadable, not a JSON object, or a known key of the wrong type (a string too long
   for its field, a setting that is no value of its render_spec row). */
int sidecar_read(const char *path, struct sidecar_info *out, struct err *e);

/* 1 when the sidecar at path exists and records job hash `hash`, else 0 (missing, unreadable,
   written for other inputs). */
int sidecar_matches(const char *path, uint64_t hash);

#endif
