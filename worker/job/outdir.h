/* outdir: a job's output folder OUT/<name>/ and the names in it (all from the output's stem), made
   on demand, locked while written, and swept of the temporary files a killed writer left. */
#ifndef OUTDIR_H
#define OUTDIR_H

#include <signal.h>
#include <stddef.h>

#include "image/image.h"
#include "job_types.h"

/* The output root when --out is not given. */
#define OUTDIR_DEFAULT "out"

/* out_dir, or OUTDIR_DEFAULT when it is NULL. */
const char *outdir_root(const char *out_dir);

/* The stem of the file at path: its name without folders or last extension ("scenes/a.b.yaml" ->
   "a.b"); a name's leading dot starts no extension (".yaml" stays ".yaml"). */
void outdir_stem(const char *path, char *out, size_t n);

/* OUT/<name>: the folder of the job, or compare job, named name. */
void outdir_dir(const char *out_dir, const char *name, char *buf, size_t n);

/* Every file a job writes, its paths computed once (outdir_files) and passed along: resume checks
   them, run_out writes them, the caller prints them. */
#define OUTDIR_IMAGES_MAX (JOB_OUTPUTS_MAX + 1) /* + a compare combination's float copy */
struct outdir_files {
    char dir[2048];                      /* OUT/<name> */
    int n_images;                        /* >= 1 */
    char image[OUTDIR_IMAGES_MAX][2048]; /* image[0]: OUT/<name>/<output>; a part: the part file */
    enum img_format format[OUTDIR_IMAGES_MAX];
    int float_copy;     /* the index of the float copy (job.float_copy), else -1 */
    char sidecar[2048]; /* OUT/<name>/<output stem>.json; a part: "" */
};

/* j's files under out_dir: its folder, each image of output: (and the float copy OUT/<name>/<output
   stem>.exr when j->float_copy and no float image is listed) and the sidecar. */
void outdir_files(const struct job *j, const char *out_dir, struct outdir_files *f);

/* The files of part I of N of j: its folder and the part file alone (outdir_part_path). */
void outdir_part_files(const struct job *j, const char *out_dir, int part, int parts, struct outdir_files *f);

/* The file of part I of N of j: OUT/<name>/<output stem>.part-I-of-N. */
void outdir_part_path(const struct job *j, const char *out_dir, int part, int parts, char *buf, size_t n);

/* 1 when file (a name in j's folder) is named as a part file of j, its I and N into *part and
 *parts; else 0. */
int outdir_part_name(const struct job *j, const char *file, int *part, int *parts);

/* Check, making nothing, that dir is a writable directory or can be made as one (so an interrupted
   render leaves no empty folder behind). 0 or -1 with e filled. */
int outdir_check(const char *dir, struct err *e);

/* mkdir -p for path, itself no symbolic link; *made (unless NULL): whether path itself was made
   here, so that a failed write may remove it. 0 or -1 with e filled. */
int outdir_mkdirs(const char *path, int *made, struct err *e);

/* 1 when the output folder's error e (its errnum) is the machine's fault, not the job's: EACCES,
   EPERM, EROFS, ENOSPC, EDQUOT. The one rule a queue worker uses to hand a claim back and stop
   (exit 2) rather than file the job as failed. */
int outdir_env_error(const struct err *e);

/* Writers of one output folder take turns: an exclusive flock() on dir while they write, so that an
   image and its sidecar always come from one render (two jobs of one name, or a worker whose queue
   claim was taken over, finishing together). Under the lock, the temporary files that a killed
   writer left for the given paths (NULL-terminated, each a file in dir) are removed. Returns the
   lock (for outdir_unlock); -1 when the folder cannot be locked (some network file systems: the
   writer goes on alone, removing nothing) or opened (errno ELOOP or ENOTDIR: a symbolic link);
   OUTDIR_STOPPED when *stop (optional) was set while it waited: write nothing; OUTDIR_WAITED_OUT
   when not had within wait_s > 0 seconds (its holder is stopped or hung; 0: wait for ever). */
#define OUTDIR_STOPPED (-2)
#define OUTDIR_WAITED_OUT (-3)
int outdir_lock(const char *dir, const char *const *paths, const volatile sig_atomic_t *stop, double wait_s);
void outdir_unlock(int lock);

/* Remove every temporary file (".<base>.tmp.XXXXXX", any writer's) from dir under its lock, for a
   job that failed; a lock held by another for over a second leaves them (they may be its). */
void outdir_remove_temps(const char *dir);

#endif
