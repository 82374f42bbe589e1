/* study_inputs: what a compare job (or a suite's studies together) reads, each file once: its
   scene files, parsed and hashed at load and handed to every render, and its reference images,
   their pixels kept for the renders' scores, the verdict and the report. */
#ifndef STUDY_INPUTS_H
#define STUDY_INPUTS_H

#include <stdint.h>

#include "base/err.h"
#include "image/image.h"
#include "job/job.h"
#include "scenefile/scene_load.h"

/* A scene file read once (scene_src_read): its parse, which run_opts.scene hands to a render, and
   its hash. */
struct study_scene {
    char path[JOB_PATH_MAX];
    struct scene_src src;
    uint64_t hash; /* FNV-1a from HASH_FNV_OFFSET over the file's bytes, then its image textures' */
};

/* What a settings reference cost and how noisy it is (compare_ref.c); 0 or NAN when unknown. */
struct study_ref_figures {
    int reused;    /* its halves came from the cache */
    double wall_s; /* seconds its render took (now or when it was cached) */
    double spp;    /* its samples per pixel (from its render or its halves' sidecars) */
    /* The mean of two independent halves: from their difference its own relMSE, mean radiance and
       that mean's standard error (an image reference's are read or unknown at the verdict). */
    double relmse, radiance, radiance_se;
};

/* A reference image read (or rendered and computed) once. */
struct study_ref {
    char path[JOB_PATH_MAX];      /* a given file, or the cache's mean (OUT/.cache/ref-<scene>-<key>.exr) */
    uint64_t scene_hash;          /* the study_scene.hash of the scene it is scored for */
    uint64_t hash;                /* scene_hash continued over the image file's bytes: each image's own hash
                                     starts there (a replaced reference makes its images stale) */
    enum img_domain domain;       /* linear, or 8-bit display values (a given PNG or PPM) */
    struct rgbf f;                /* what images are scored against, in domain */
    struct rgb8 display;          /* as 8-bit display values (an EXR's floats as the PNG writer makes them) */
    struct study_ref_figures fig; /* a settings reference's, over the whole image */
};

struct study_inputs {
    struct study_scene **scenes;
    int n_scenes, cap_scenes;
    struct study_ref **refs;
    int n_refs, cap_refs;
    uint64_t program_hash; /* FNV-1a of /proc/self/exe (0 until asked; unreadable: the offset) */
};

/* An empty set, or NULL (out of memory). Free with study_inputs_free (NULL is fine). */
struct study_inputs *study_inputs_new(void);
void study_inputs_free(struct study_inputs *in);

/* The scene file at path, read and parsed on the first ask, kept by in. NULL with e when it
   cannot be read (a scene that does not parse is found by scene_load_src of its src). */
const struct study_scene *study_inputs_scene(struct study_inputs *in, const char *path, struct err *e);

/* The reference image at path scored for a scene of hash scene_hash, if in holds it; else NULL. */
const struct study_ref *study_inputs_find_ref(const struct study_inputs *in, const char *path,
                                              uint64_t scene_hash);

/* Keep r (its pixels taken over; r is emptied) in in. The kept copy, or NULL (out of memory, e;
   r's pixels freed). */
const struct study_ref *study_inputs_keep_ref(struct study_inputs *in, struct study_ref *r, struct err *e);

/* r's pixels from an image file's bytes (data, len; read once from path): its floats, domain,
   display values and hash (scene_hash continued over data). 0, or -1 with e; r's pixels freed. */
int study_ref_decode(struct study_ref *r, const char *path, uint64_t scene_hash, const uint8_t *data,
                     size_t len, struct err *e);
void study_ref_free(struct study_ref *r);

/* The worker program's own bytes hashed, once per in (a reference cache's key). */
uint64_t study_inputs_program_hash(struct study_inputs *in);

#endif
