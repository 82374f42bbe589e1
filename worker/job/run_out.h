/* run_out: a job's outputs written into its folder (outdir.h: names, making, locking): the image
   and its sidecar atomically, under the folder's lock and the run's permission to write. */
#ifndef RUN_OUT_H
#define RUN_OUT_H

#include <signal.h>

#include "run.h"

/* Whether the render may still rename an output into place (run_opts.still_held): 0, or -1 with e
   filled (the claim was taken over while it wrote). */
int run_out_still_held(const struct run_opts *o, const char *dir, struct err *e);

/* Take dir's lock for writing paths (outdir_lock) into *lock, then ask whether this render may
   still write (run_opts.may_write): a claim taken over while we waited for the lock (another
   writer, a slow disk) writes nothing, nor does a writer stopped while it waited. A lock not had
   within o->lock_wait_s (> 0) is held by a stopped or hung writer, whose claim was taken over (it
   checks before each rename, run_out_still_held, and gives up): this writer goes on without it,
   saying so, when may_write says yes. 0, or -1 with e filled; outdir_unlock(*lock) either way. */
int run_out_lock_outputs(const char *dir, const char *const *paths, const struct run_opts *o, int *lock,
                         struct err *e);

/* Write the linear framebuffer rgb (w x h) as the job's image (PNG/PPM: converted to 8 bits;
   EXR/PFM: the floats as they are), with its float copy (j->float_copy) and sidecar (paths from
   outdir_paths under o->out_dir, into rr), all atomically. With a reference (ref not NULL, ref->px
   set) score it into rr->error: on the linear floats when ref_domain is IMG_LINEAR, else on the
   8-bit image's display values. parts > 0 marks a merge of that many part files; rr->black: the
   image is entirely black. 0 or -1 with e filled (nothing left behind). */
int run_out_write(const struct job *j, const struct run_opts *o, const float *rgb, int w, int h,
                  const struct procs_result *fr, const struct rgbf *ref, enum img_domain ref_domain,
                  int parts, struct run_result *rr, struct err *e);

/* Write rows o->part of o->parts of the framebuffer rgb (w x h) into j's part file (its path into
   rr->image_path; rr->sidecar_path ""), under the folder's lock as run_out_write. 0 or -1 with e
   filled (nothing left behind). */
int run_out_write_part(const struct job *j, const struct run_opts *o, const float *rgb, int w, int h,
                       const struct procs_result *fr, struct run_result *rr, struct err *e);

#endif
