/* run_out: a job's outputs written into its folder (outdir.h: names, making, locking): the image
   and its sidecar atomically, under the folder's lock and the run's permission to write. */
#ifndef RUN_OUT_H
#define RUN_OUT_H

#include <signal.h>

#include "run_types.h"

/* Take dir's lock for writing paths (outdir_lock) into *lock, then ask run_opts.may_write: a claim
   taken over while it waited writes nothing. A lock not had within o->lock_wait_s (> 0) is a hung
   writer's, who gives up at its next rename: this one goes on without it, saying so. 0, or -1 with
   e filled (also when stopped while waiting); outdir_unlock(*lock) either way. */
int run_out_lock_outputs(const char *dir, const char *const *paths, const struct run_opts *o, int *lock,
                         struct err *e);

/* A rendered (or merged) framebuffer on its way to disk. */
struct run_frame {
    const float *rgb; /* linear radiance, w x h x 3 */
    int w, h;
    const struct procs_result *procs;
    const struct rgbf *ref;     /* optional: the reference (ref->px NULL: none) */
    enum img_domain ref_domain; /* what ref holds */
    int parts;                  /* > 0: merged from that many part files */
};

/* Write frame f as j's files rr->out (computed by the caller): each image in its format (PNG/PPM
   in 8 bits, EXR/PFM the floats), then the sidecar; each staged once under a temporary name and,
   when all are, renamed once, the sidecar last. With a reference, f scored into rr->error (on the
   floats when f->ref_domain is IMG_LINEAR, else on the 8-bit values). rr->black: the image is
   entirely black. 0 or -1 with e filled (nothing left behind). */
int run_out_write(const struct job *j, const struct run_opts *o, const struct run_frame *f,
                  struct run_result *rr, struct err *e);

/* Write rows o->part of o->parts of frame f into j's part file rr->out.image[0], under the
   folder's lock as run_out_write. 0 or -1 with e filled (nothing left behind). */
int run_out_write_part(const struct job *j, const struct run_opts *o, const struct run_frame *f,
                       struct run_result *rr, struct err *e);

#endif
