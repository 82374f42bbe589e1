/* run_out: a job's output folder: made on demand, locked while written (a killed writer's
   temporaries removed under the lock), and the image and sidecar written there atomically. */
#ifndef RUN_OUT_H
#define RUN_OUT_H

#include <signal.h>

#include "run.h"

/* mkdir -p for path. 0 or -1 with e filled. */
int run_out_mkdirs(const char *path, struct err *e);

/* Make dir (and its parents) for outputs about to be written; *made: whether dir itself was made
   here, so a failed write may remove it. A folder that was there already, or that another process
   made meanwhile, is never ours to remove. */
int run_out_make_dir(const char *dir, int *made, struct err *e);

/* Writers of one output folder take turns: an exclusive flock() on dir while they write, so that
   an image and its sidecar always come from one render (two jobs of one name, or a worker whose
   queue claim was taken over, finishing together). Under the lock, the temporary files that a
   killed writer left for the given paths (NULL-terminated) are removed: a lock holder's own
   temporary files never outlive its lock. Returns the lock (for run_out_unlock), or -1 when the
   folder cannot be locked (some network file systems): the writer goes on alone, removing
   nothing; RUN_OUT_STOPPED when *stop (optional) was set by a signal while it waited: write
   nothing; RUN_OUT_WAITED_OUT when wait_s > 0 and the lock was not had within wait_s seconds
   (its holder is stopped or hung). wait_s 0: wait as long as it takes. */
#define RUN_OUT_STOPPED (-2)
#define RUN_OUT_WAITED_OUT (-3)
int run_out_lock(const char *dir, const char *const *paths, const volatile sig_atomic_t *stop, double wait_s);
void run_out_unlock(int lock);

/* Whether the render may still rename an output into place (run_opts.still_held): 0, or -1 with e
   filled (the claim was taken over while it wrote). */
int run_out_still_held(const struct run_opts *o, const char *dir, struct err *e);

/* Remove every temporary file (".<base>.tmp.XXXXXX", any writer's) from dir, under its lock: for a
   job that ends without writing (failed), so that a killed writer's leftovers do not outlive it.
   A lock held by another writer for over a second leaves them (they may be that writer's). */
void run_out_remove_temps(const char *dir);

/* Take dir's lock for writing paths (run_out_lock) into *lock, then ask whether this render may
   still write (run_opts.may_write): a claim taken over while we waited for the lock (another
   writer, a slow disk) writes nothing, nor does a writer stopped while it waited. A lock not had
   within o->lock_wait_s (> 0) is held by a stopped or hung writer, whose claim was taken over (it
   checks before each rename, run_out_still_held, and gives up): this writer goes on without it,
   saying so, when may_write says yes. 0, or -1 with e filled; run_out_unlock(*lock) either way. */
int run_out_lock_outputs(const char *dir, const char *const *paths, const struct run_opts *o, int *lock,
                         struct err *e);

/* Write the linear framebuffer rgb (w x h) as the job's image (PNG/PPM: converted to 8 bits;
   EXR/PFM: the floats as they are), with its float copy (j->float_copy) and sidecar (paths from
   run_paths under o->out_dir, into rr), all atomically. With a reference (ref not NULL, ref->px
   set) score it into rr->error: on the linear floats when ref_domain is IMG_LINEAR, else on the
   8-bit image's display values. parts > 0 marks a merge of that many part files; rr->black: the
   image is entirely black. 0 or -1 with e filled (nothing left behind). */
int run_out_write(const struct job *j, const struct run_opts *o, const float *rgb, int w, int h,
                  const struct procs_result *fr, const struct rgbf *ref, enum img_domain ref_domain,
                  int parts, struct run_result *rr, struct err *e);

#endif
