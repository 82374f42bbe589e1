/* job: one render job as read from a YAML job file, validated strictly. */
#ifndef JOB_H
#define JOB_H

#include <stdint.h>

#include "base/err.h"
#include "image/image.h"
#include "sample/sampler.h"
#include "scenefile/yamlx.h"

#define JOB_PATH_MAX 1024
#define JOB_NAME_MAX 128
#define JOB_OUTPUTS_MAX 4 /* images one job writes: one per format */

struct job {
    char path[JOB_PATH_MAX]; /* the job file */
    char name[JOB_NAME_MAX];
    char scene_path[JOB_PATH_MAX]; /* resolved */
    int width, height;             /* height 0: width / camera aspect */
    enum sampler_kind sampler, light_sampler;
    double threshold, light_threshold;
    int max_depth;
    uint64_t seed;
    int processes;
    enum img_format format;
    char output[JOB_NAME_MAX]; /* the image's file name under --out DIR/<name>/ (a list's first): its
                                  stem names the sidecar and the part files */
    int n_more;                /* output: [a.png, a.exr]: the images written beside it, one per format */
    char more_output[JOB_OUTPUTS_MAX - 1][JOB_NAME_MAX];
    enum img_format more_format[JOB_OUTPUTS_MAX - 1];
    char reference[JOB_PATH_MAX]; /* resolved; "" when none */
    int poisson_pool;
    enum poisson_domain poisson_domain; /* fresh Poisson sets: torus (default, unbiased) or square */
    int light_sampling;                 /* 0: no importance sampling of lights (default 1) */
    int nee;            /* integrator: 1 next-event estimation with MIS, 0 the books' mixture (default) */
    int dims_all;       /* sampler_dims: 1 all (every 2D decision from the sampler), 0 pixel_light */
    int roulette;       /* russian_roulette: 1 on, 0 off, -1 not given (job_roulette: on with nee) */
    int priority;       /* queue order: higher first (default 0) */
    double entry_cpu_s; /* a study spread over a queue: its entries' CPU target; 0: the queue's */
    int float_copy;     /* not a key: also write the framebuffer as <stem>.exr beside a PNG or PPM
                           image (a compare job's renders, scored in linear radiance) */
    uint64_t hash;      /* FNV-1a of the job file's bytes, then its scene file's */
    /* which keys were given, and where (1-based line, col; 0 when absent) */
    int has_light_sampler, has_format, has_output;
    int pos_threshold[2], pos_light_threshold[2], pos_light_sampler[2], pos_dims[2], pos_reference[2],
        pos_scene[2], pos_format[2], pos_output[2], pos_name[2], pos_width[2], pos_poisson_pool[2];
};

/* The smallest threshold sampler kind k takes (its sets stay within SAMPLER_MAX_POINTS). */
double job_smallest_threshold(enum sampler_kind k);

/* Read the job in the parsed document d of the job file at path (relative scene and reference
   paths resolve beside path) into j: every key checked, defaults filled; j->hash left 0 (the
   job file's reader, jobfile_open, sets it). 0, or -1 with e = "file:line:col: key: message". */
int job_from_doc(struct ydoc *d, const char *path, struct job *j, struct err *e);

/* Whether the job's paths may end by Russian roulette: russian_roulette when given, else on with
   integrator: nee and off with the mixture (whose images stay the books'). */
int job_roulette(const struct job *j);

/* The image height j renders at: its height:, else its width / the camera's aspect, rounded, at
   least 1 (the caller checks it against IMAGE_MAX_SIDE). */
int job_height(const struct job *j, double aspect);

/* Set defaults (name from the file's stem). */
void job_defaults(struct job *j, const char *path);

/* Apply one key/value pair of a job mapping to j (used for job files and compare variants). */
int job_apply(struct job *j, struct ydoc *d, yaml_node_t *key, yaml_node_t *val, struct err *e);

/* A job without name: is named for its file's stem, which must fit a name (JOB_NAME_MAX - 1
   bytes): a longer stem is refused, never cut (two files differing after the cut would share an
   output folder, and a cut may split a UTF-8 character). 0, or -1 with e filled (at 1:1). */
int job_check_stem(const struct job *j, struct err *e);

/* Derive what depends on several keys (light sampler default, format, output name). */
int job_finish(struct job *j, struct ydoc *d, struct err *e);

/* What a cache key must add for the sets j's samplers make beyond the keys it prints: the Poisson
   domain when a sampler is poisson, the padding's version under sampler_dims: all ("" else), so
   an image rendered by an earlier rule is never found current. */
const char *job_sets_tag(const struct job *j);

/* Where j's light points really come from, for a caption: "light jitter t=5", or under
   sampler_dims: all (which never asks the light sampler) "light points from the sobol sets
   (sampler_dims: all)", or "no light sampling". Written into buf (n bytes), returned. */
const char *job_light_text(const struct job *j, char *buf, size_t n);

/* The keys a job file may hold, NULL-terminated. */
extern const char *const job_keys[];

#endif
