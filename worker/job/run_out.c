/* run_out: make, lock and write a job's output folder (image and sidecar, atomically). */
#include "run_out.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "base/fileio.h"
#include "image/imgio.h"
#include "image/metrics.h"
#include "sidecar.h"

/* Make path and its parents; *made (unless NULL): whether path itself was made here. */
static int mkdirs(const char *path, int *made, struct err *e)
{
    char buf[2048];
    snprintf(buf, sizeof buf, "%s", path);
    if (made)
        *made = 0;
    for (char *p = buf + 1;; p++) {
        if (*p == '/' || *p == 0) {
            char c = *p;
            *p = 0;
            int ok = mkdir(buf, 0755) == 0;
            if (!ok && errno != EEXIST)
                return err_set(e, NULL, 0, 0, "cannot create directory %s: %s", buf, strerror(errno));
            struct stat st;
            if (stat(buf, &st) < 0 || !S_ISDIR(st.st_mode))
                return err_set(e, NULL, 0, 0, "cannot create directory %s: a file is in the way", buf);
            *p = c;
            if (!c) {
                if (made)
                    *made = ok;
                break;
            }
        }
    }
    return 0;
}

int run_out_mkdirs(const char *path, struct err *e)
{
    return mkdirs(path, NULL, e);
}

int run_out_make_dir(const char *dir, int *made, struct err *e)
{
    return mkdirs(dir, made, e);
}

/* Whether n is a temporary of the file named base: fileio_write_atomic's ".<base>.tmp.XXXXXX", or
   its own temporary of such a staging file, "..<base>.tmp.XXXXXX.tmp.YYYYYY". */
static int is_temp_of(const char *n, const char *base)
{
    size_t bl = strlen(base);
    if (n[0] != '.')
        return 0;
    const char *t = !strncmp(n + 1, base, bl)                  ? n + 1 + bl
                    : n[1] == '.' && !strncmp(n + 2, base, bl) ? n + 2 + bl
                                                               : NULL;
    if (!t || strncmp(t, ".tmp.", 5) != 0)
        return 0;
    size_t rest = strlen(t + 5);
    return t == n + 1 + bl ? rest == 6 : rest == 17 && !strncmp(t + 11, ".tmp.", 5);
}

/* Remove the temporaries that writers killed half-way left for path beside it (is_temp_of). Only
   the holder of the folder's lock may call it. */
static void remove_dead_temps(const char *path)
{
    char dir[2048];
    const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path;
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) : 1, slash ? path : ".");
    DIR *d = opendir(dir);
    if (!d)
        return;
    struct dirent *de;
    while ((de = readdir(d))) {
        if (is_temp_of(de->d_name, base)) {
            char dead[4096];
            snprintf(dead, sizeof dead, "%s/%s", dir, de->d_name);
            unlink(dead);
        }
    }
    closedir(d);
}

int run_out_lock(const char *dir, const char *const *paths, const volatile sig_atomic_t *stop)
{
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC), rc = -1;
    if (fd < 0)
        return -1;
    /* a stop signal interrupts the wait (the queue's handlers have no SA_RESTART): a holder that
       hangs must not make this writer deaf to it */
    while ((rc = flock(fd, LOCK_EX)) < 0 && errno == EINTR && !(stop && *stop))
        ;
    if (rc < 0) {
        int stopped = errno == EINTR;
        close(fd);
        return stopped ? RUN_OUT_STOPPED : -1;
    }
    for (int i = 0; paths && paths[i]; i++)
        remove_dead_temps(paths[i]);
    return fd;
}

void run_out_unlock(int fd)
{
    if (fd >= 0)
        close(fd); /* closing the last descriptor of the open folder releases the flock */
}

/* A staging name for path, unique to this writer: "<dir>/.<base>.tmp.XXXXXX" with six letters
   or digits from the pid and the time, shaped as fileio_write_atomic's temporaries so that a
   writer killed between staging and renaming leaves nothing for good (is_temp_of). */
static void staged_name(const char *path, char *out, size_t n)
{
    static const char alnum[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t x = rng_mix64((uint64_t)getpid() << 32 ^ (uint64_t)ts.tv_sec << 30 ^ (uint64_t)ts.tv_nsec);
    char suffix[7];
    for (int i = 0; i < 6; i++, x /= 62)
        suffix[i] = alnum[x % 62];
    suffix[6] = 0;
    const char *slash = strrchr(path, '/');
    int dl = slash ? (int)(slash - path) + 1 : 0;
    snprintf(out, n, "%.*s.%s.tmp.%s", dl, path, path + dl, suffix);
}

/* An error about writing the staging file `staged` names the final path instead. */
static void name_final(struct err *e, const char *staged, const char *final)
{
    char *at = strstr(e->msg, staged);
    if (!at)
        return;
    char msg[sizeof e->msg];
    snprintf(msg, sizeof msg, "%.*s%s%s", (int)(at - e->msg), e->msg, final, at + strlen(staged));
    snprintf(e->msg, sizeof e->msg, "%s", msg);
    if (!strcmp(e->file, staged))
        snprintf(e->file, sizeof e->file, "%s", final);
}

int run_out_lock_outputs(const char *dir, const char *const *paths, const struct run_opts *o, int *lock,
                         struct err *e)
{
    *lock = run_out_lock(dir, paths, o->stop);
    if (*lock == RUN_OUT_STOPPED)
        return err_set(e, NULL, 0, 0, "stopped while waiting for another writer of %s/: nothing written",
                       dir);
    if (!o->may_write || o->may_write(o->tick_arg, dir))
        return 0;
    return err_set(e, NULL, 0, 0,
                   "rendered, but it may not write %s/ now (another worker holds the job, or the folder is "
                   "another job's): nothing written",
                   dir);
}

int run_out_write(const struct job *j, const struct run_opts *o, const float *rgb, int w, int h,
                  const struct procs_result *fr, const struct rgb8 *ref, int parts, struct run_result *rr,
                  struct err *e)
{
    char dir[2048], staged_image[2100], staged_sidecar[2100];
    struct rgb8 img = {0};
    char *json = NULL;
    int rc = -1, made_dir = 0, lock = -1;
    run_paths(j, o->out_dir, dir, rr->image_path, rr->sidecar_path, sizeof rr->image_path);
    if (run_out_make_dir(dir, &made_dir, e) < 0 || image_alloc(&img, w, h, e) < 0)
        goto done;
    staged_name(rr->image_path, staged_image, sizeof staged_image);
    staged_name(rr->sidecar_path, staged_sidecar, sizeof staged_sidecar);
    const char *outs[] = {rr->image_path, rr->sidecar_path, NULL};
    if (run_out_lock_outputs(dir, outs, o, &lock, e) < 0)
        goto done;
    image_float_to_rgb8(rgb, w, h, img.px);
    struct metrics m;
    int has_ref = ref && ref->px;
    if (has_ref && metrics_display_compare(ref, &img, &m, e) < 0)
        goto done;
    struct sidecar sc = {j, w, h, fr, has_ref ? &m : NULL, j->output, parts};
    if (!(json = sidecar_json(&sc))) {
        err_set(e, NULL, 0, 0, "out of memory writing the sidecar");
        goto done;
    }
    /* Both are written whole under staging names first, then renamed, the image first: a failure
       before the renames (a full disk, a size limit) leaves an earlier image and sidecar as they
       were. A killed writer's staged files and their temporaries go under the next one's lock. */
    if (imgio_write(staged_image, &img, j->format, e) < 0) {
        name_final(e, staged_image, rr->image_path);
        goto done;
    }
    if (fileio_write_atomic(staged_sidecar, json, strlen(json), e) < 0) {
        name_final(e, staged_sidecar, rr->sidecar_path);
        unlink(staged_image);
        goto done;
    }
    if (rename(staged_image, rr->image_path) < 0) {
        err_set(e, NULL, 0, 0, "cannot write %s: %s", rr->image_path, strerror(errno));
        unlink(staged_image);
        unlink(staged_sidecar);
        goto done;
    }
    if (rename(staged_sidecar, rr->sidecar_path) < 0) {
        err_set(e, NULL, 0, 0, "cannot write %s: %s", rr->sidecar_path, strerror(errno));
        unlink(staged_sidecar);
        unlink(rr->image_path); /* an image without its sidecar is not a finished job */
        goto done;
    }
    rc = 0;
done:
    run_out_unlock(lock);
    if (rc != 0 && made_dir)
        rmdir(dir); /* a failed write leaves no empty folder of ours (it fails when not empty) */
    free(json);
    image_free(&img);
    return rc;
}
