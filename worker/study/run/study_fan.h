/* study_fan: a compare job or suite taken apart into its renders (one per reference, one per
   image), each run alone, for a queue's fan-out; the gather is jobfile_run with every render
   current. */
#ifndef STUDY_FAN_H
#define STUDY_FAN_H

#include "job/run.h"
#include "study/load/compare_model.h"
#include "job/jobfile.h"

/* A loaded compare job: a plain one (c) or a suite (s), one of them. */
struct study_fan {
    struct compare *c;
    struct compare_suite *s;
};

/* What one render of a study is. */
enum study_fan_kind { STUDY_FAN_REFERENCE, STUDY_FAN_IMAGE };

/* Which render: study k's half `half` (0 or 1) of scene `index`'s reference, or its image `index`. */
struct study_fan_which {
    int k;
    enum study_fan_kind kind;
    int index, half;
};

/* Load the compare job or suite from the job file jobfile_open read and parsed (jf->kind not
   JOBFILE_PLAIN). 0 or -1 with e = "file:line:col: key: message". */
int study_fan_load(const struct jobfile *jf, struct study_fan *f, struct err *e);
void study_fan_free(struct study_fan *f);

/* The job's name, its number of studies (1 for a plain compare job) and study k. */
const char *study_fan_name(const struct study_fan *f);
int study_fan_studies(const struct study_fan *f);
struct compare *study_fan_study(const struct study_fan *f, int k);

/* 1 when scene s of study k has a reference to render (settings, not an image). */
int study_fan_has_reference(const struct study_fan *f, int k, int s);

/* Render study k's reference of scene `index` or its image `index` alone, into o->out_dir as the
   whole job would (a suite's studies under OUT/<suite>/), skipping what is current. Returns
   compare_run's 0, 1 or 2 with e filled. */
int study_fan_render(struct study_fan *f, int k, enum study_fan_kind kind, int index,
                     const struct run_opts *o, struct err *e);

/* Render w as a queue cuts it into row parts: a reference's half (compare_ref_half_target) or an
   image (compare_item_job: its scene's reference prepared first), its job in *j and the options it
   renders with in *jo (o's, with its out_dir in dir of n bytes for a suite's study and the scene as
   the study read it, valid while f is). Returns 0, 3 when a reference half is already in the cache,
   or compare_run's 1 or 2 with e filled. */
int study_fan_render_job(struct study_fan *f, const struct study_fan_which *w, const struct run_opts *o,
                         struct job *j, struct run_opts *jo, char *dir, size_t n, struct err *e);

/* Study k's reference half h of scene s rendered whole into the cache (or found there); or, merged
   from its parts by the caller, recorded there. 0, 1 or 2 (merged: 0 or 1) with e filled. */
int study_fan_render_half(struct study_fan *f, int k, int s, int h, const struct run_opts *o, struct err *e);
int study_fan_half_merged(struct study_fan *f, int k, int s, int h, const struct run_opts *o, struct err *e);

/* The lock of study k's reference of scene s (OUT/.cache/.ref-<scene>.lock, a suite's under
   OUT/<suite>/), taken shared (the tasks rendering its halves or their parts) or exclusive (a task
   about to prepare it whole: it waits for those): the open file, to close; -1 with e filled when
   the cache folder cannot be made, -1 with e empty when the lock cannot be opened (go on without). */
int study_fan_ref_lock(const struct study_fan *f, int k, int s, const struct run_opts *o, int shared,
                       struct err *e);

/* `worker STUDY.yaml --out OUT --part I/N`: a batch system's task I of N renders the images with
   index % N == I (over all studies of a suite), each after its scene's reference, which the first
   task to need it renders under a lock (OUT/.cache/.ref-<scene>.lock) while the others wait and
   then reuse it. Images already current are skipped (resume by job hash). No summary: the gather
   is the whole job run afterwards (`worker STUDY.yaml --out OUT`), every render then current.
   One line at the end; returns the exit status 0, 1 or 2. */
int study_fan_share(const struct jobfile *jf, const struct run_opts *o);

#endif
