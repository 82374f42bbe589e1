/* run: render one loaded job end to end (scene, samplers, forked render processes, image, sidecar). */
#ifndef RUN_H
#define RUN_H

#include "run_types.h"

/* Render j into rr->out's files (computed here), written atomically once it completed. 0; 2 when
   the job's input is bad (nothing rendered); 1 when rendering or writing failed; e says why.
   Unless o->force, a job whose outputs exist and record j->hash (non-zero: the job was read by
   jobfile_open) is not rendered: 0, rr->skipped. */
int run_job(const struct job *j, const struct run_opts *o, struct run_result *rr, struct err *e);

/* Read j's reference into ref as floats (*domain: what they are) and check it is w x h. 0 (ref->px
   NULL when the job has none), or -1 with e at the job's reference key. */
int run_load_reference(const struct job *j, int w, int h, struct rgbf *ref, enum img_domain *domain,
                       struct err *e);

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
