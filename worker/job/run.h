/* run: render one loaded job end to end (scene, samplers, forked render processes, image, sidecar). */
#ifndef RUN_H
#define RUN_H

#include <signal.h>

#include "image/metrics.h"
#include "job.h"
#include "outdir.h"
#include "procs.h"
#include "scenefile/scene_load.h"

struct run_opts {
    const char *out_dir; /* NULL: OUTDIR_DEFAULT (outdir.h) */
    int processes;       /* > 0 overrides the job's */
    int quiet;
    int progress;                      /* draw progress on stderr (a terminal, not quiet) */
    int force;                         /* render even when the outputs are current (resume off) */
    int part, parts;                   /* parts > 0: render rows with row % parts == part into a part file */
    const volatile sig_atomic_t *stop; /* optional: abandon the render when it becomes non-zero */
    void (*tick)(void *arg, int rows_done, int rows, double elapsed_s); /* optional: about every 5 ms
                                          while rendering, with its progress */
    int (*may_write)(void *arg, const char *dir); /* optional: asked (with tick_arg and the output
                                          folder) under that folder's lock, just before writing;
                                          0 = write nothing, fail (a queue claim taken over, the
                                          folder another queued job's) */
    void *tick_arg;
    double lock_wait_s;            /* > 0: wait no longer for the output folder's lock (a queue: its lease
                                      timeout); then its holder is stopped or hung, and this render writes
                                      without it when may_write still says yes */
    int (*still_held)(void *arg);  /* optional: asked (with tick_arg) just before each output is
                                      renamed into place: 0 = the claim was taken over meanwhile;
                                      rename nothing more, fail */
    const struct scene_src *scene; /* optional: the job's scene, already read and parsed (jobfile_open);
                                      NULL: run_job reads j->scene_path itself */
    const struct rgbf *ref;        /* optional: the job's reference, already read (a compare job reads each
                                      scene's once); NULL: run_job reads j->reference itself */
    enum img_domain ref_domain;    /* what ref holds (IMG_DISPLAY8: 8-bit display values) */
    const uint8_t *ref_bytes;      /* optional, without ref: j->reference's bytes, already read
                                      (jobfile_open); NULL: run_job reads the file */
    size_t ref_len;
    const char *label;              /* optional: the progress line's name; NULL: the job's name (a
                                       compare reference's name is its folder, ".cache") */
    const struct rgb8 *ref_display; /* optional: the reference as 8-bit display values: the PNG or
                                       PPM image is also scored against it (display_error) */
};

struct run_result {
    struct outdir_files out; /* what the job writes (with parts: the part file), computed once */
    int width, height;
    int skipped;               /* outputs were current (same job hash): nothing rendered */
    int black;                 /* the image written is entirely black (run_print_warnings) */
    char scene_warning[600];   /* the scene's warning (scene_file.warning), run_print_warnings's */
    struct procs_result procs; /* on a render failure: child_crashed, child_signal, stopped */
    int has_error;             /* rendered against a reference: error holds the figures */
    struct metrics error;
    int has_display_error;        /* o->ref_display given and the image is PNG or PPM */
    struct metrics display_error; /* the 8-bit image against o->ref_display */
    enum img_domain error_domain; /* linear radiance, or 8-bit display values (a PNG/PPM reference) */
};

/* Render j. Returns 0 on success, 2 when the job's input is bad (scene, reference: nothing
   rendered), 1 when rendering or writing failed; e says why. No output file exists unless the
   render completed: images and sidecar are written atomically. rr->out: the files' paths,
   computed once here. Unless o->force, a job whose images and sidecar (or part file) exist and
   record j->hash (non-zero: the job was read by jobfile_open) is not rendered: 0, rr->skipped. */
int run_job(const struct job *j, const struct run_opts *o, struct run_result *rr, struct err *e);

/* Read j's reference (EXR, PFM, PNG or PPM) into ref as floats, *domain saying what they are,
   and check it is w x h. 0 (ref->px NULL when the job has none), or -1 with e at the job's
   reference key. */
int run_load_reference(const struct job *j, int w, int h, struct rgbf *ref, enum img_domain *domain,
                       struct err *e);

/* run_load_reference of the reference's bytes already read (data, len). */
int run_decode_reference(const struct job *j, const uint8_t *data, size_t len, int w, int h, struct rgbf *ref,
                         enum img_domain *domain, struct err *e);

/* The one-line warning on stderr that the error against the reference at path is measured on
   8-bit display values (a PNG or PPM reference), not on linear radiance. */
void run_warn_display_reference(const char *job_name, const char *path);

/* A progress line on stderr, printed only when o->progress (a terminal) and not o->quiet. */
void run_say(const struct run_opts *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The one summary line of a rendered job on stderr (size, sampler, spp, processes, time, image),
   then its warnings (run_print_warnings). */
void run_print_summary(const struct job *j, const struct run_result *rr);

/* run_print_summary's line and run_print_warnings' into buf (no newline); run_format_warning
   returns 0 when there is none. */
void run_format_summary(const struct job *j, const struct run_result *rr, char *buf, size_t n);
int run_format_warning(const struct job *j, const struct run_result *rr, char *buf, size_t n);

/* A line on stderr, naming the job, for what an exit code of 0 would hide: an entirely black
   image (no light reaches the camera: a light facing away, lights missing). */
void run_print_warnings(const struct job *j, const struct run_result *rr);

#endif
