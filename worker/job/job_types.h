/* job_types: struct job, the one type every part of a job (job_path, outdir) shares, in a header
   of its own so that they include this and never job.h, whose source calls them. */
#ifndef JOB_TYPES_H
#define JOB_TYPES_H

#include <stdint.h>

#include "base/err.h"
#include "image/image.h"
#include "render/integrator.h"
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
    enum integrator integrator;         /* integrator: (integrator.h), the books' mixture by default */
    int dims_all; /* sampler_dims: 1 all (every 2D decision from the sampler), 0 pixel_light */
    int roulette; /* russian_roulette: 1 on, 0 off, -1 not given (job_roulette: the integrator's default) */
    int priority; /* queue order: higher first (default 0) */
    double entry_cpu_s; /* a study spread over a queue: its entries' CPU target; 0: the queue's */
    int float_copy;     /* not a key: also write the framebuffer as <stem>.exr beside a PNG or PPM
                           image (a compare job's renders, scored in linear radiance) */
    uint64_t hash;      /* FNV-1a of the job file's bytes, then its scene file's */
    /* which keys were given, and where (1-based line, col; 0 when absent) */
    int has_light_sampler, has_format, has_output;
    int pos_threshold[2], pos_light_threshold[2], pos_light_sampler[2], pos_dims[2], pos_reference[2],
        pos_scene[2], pos_format[2], pos_output[2], pos_name[2], pos_width[2], pos_poisson_pool[2];
};

#endif
