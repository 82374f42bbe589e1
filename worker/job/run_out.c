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
            /* the folder itself is never a symbolic link: outputs would land wherever it points */
            if (!c && lstat(buf, &st) == 0 && S_ISLNK(st.st_mode))
                return err_set(e, NULL, 0, 0,
                               "%s is a symbolic link: outputs are never written through one (make it a "
                               "folder)",
                               buf);
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

/* Whether n is any writer's temporary (is_temp_of, whatever the file): ".<base>.tmp.XXXXXX". */
static int is_temp(const char *n)
{
    size_t len = strlen(n);
    return n[0] == '.' && len > 12 && !strncmp(n + len - 11, ".tmp.", 5);
}

void run_out_remove_temps(const char *dir)
{
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC), locked = 0;
    if (fd < 0)
        return;
    for (int i = 0; i < 100 && !(locked = flock(fd, LOCK_EX | LOCK_NB) == 0); i++) {
        struct timespec nap = {0, 10 * 1000 * 1000};
        nanosleep(&nap, NULL);
    }
    DIR *d = locked ? fdopendir(dup(fd)) : NULL;
    struct dirent *de;
    while (d && (de = readdir(d)))
        if (is_temp(de->d_name))
            (void)unlinkat(fd, de->d_name, 0);
    if (d)
        closedir(d);
    close(fd); /* and the lock with it */
}

/* flock(fd, LOCK_EX) for at most wait_s seconds (> 0) in 20 ms steps; -1 with errno EWOULDBLOCK
   when waited out, EINTR when *stop was set meanwhile. */
static int lock_within(int fd, double wait_s, const volatile sig_atomic_t *stop)
{
    struct timespec t0, now, nap = {0, 20 * 1000 * 1000};
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (;;) {
        if (flock(fd, LOCK_EX | LOCK_NB) == 0)
            return 0;
        if (errno != EWOULDBLOCK && errno != EINTR)
            return -1;
        if (stop && *stop) {
            errno = EINTR;
            return -1;
        }
        clock_gettime(CLOCK_MONOTONIC, &now);
        if ((now.tv_sec - t0.tv_sec) + (now.tv_nsec - t0.tv_nsec) * 1e-9 > wait_s) {
            errno = EWOULDBLOCK;
            return -1;
        }
        nanosleep(&nap, NULL);
    }
}

int run_out_lock(const char *dir, const char *const *paths, const volatile sig_atomic_t *stop, double wait_s)
{
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC), rc = -1; /* a link swapped in */
    if (fd < 0)
        return -1;
    /* a stop signal interrupts the wait (the queue's handlers have no SA_RESTART): a holder that
       hangs must not make this writer deaf to it */
    if (wait_s > 0)
        rc = lock_within(fd, wait_s, stop);
    else
        while ((rc = flock(fd, LOCK_EX)) < 0 && errno == EINTR && !(stop && *stop))
            ;
    if (rc < 0) {
        int why = errno;
        close(fd);
        return why == EINTR ? RUN_OUT_STOPPED : why == EWOULDBLOCK ? RUN_OUT_WAITED_OUT : -1;
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
    *lock = run_out_lock(dir, paths, o->stop, o->lock_wait_s);
    if (*lock == RUN_OUT_WAITED_OUT && (!o->may_write || o->may_write(o->tick_arg, dir)))
        err_print("%s/: its lock has been held for over %g s (a lease timeout) by a writer that is stopped "
                  "or hung: writing without it\n",
                  dir, o->lock_wait_s);
    if (*lock == -1 && (errno == ELOOP || errno == ENOTDIR))
        return err_set(e, NULL, 0, 0, "%s is a symbolic link: outputs are never written through one", dir);
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

int run_out_still_held(const struct run_opts *o, const char *dir, struct err *e)
{
    if (!o->still_held || o->still_held(o->tick_arg))
        return 0;
    return err_set(e, NULL, 0, 0, "the claim was taken over while it wrote %s/: nothing written", dir);
}

/* The EXR header's string attributes for j (nothing that depends on the process count or the
   output folder: the file's bytes do not). texts holds their values. */
static size_t exr_attrs(const struct job *j, struct img_attr *a, char texts[][160])
{
    const char *slash = strrchr(j->scene_path, '/');
    snprintf(texts[0], 160, "%s", slash ? slash + 1 : j->scene_path);
    snprintf(texts[1], 160, "%s t=%.17g", sampler_kind_name(j->sampler), j->threshold);
    snprintf(texts[2], 160, "%s t=%.17g", sampler_kind_name(j->light_sampler), j->light_threshold);
    snprintf(texts[3], 160, "%llu", (unsigned long long)j->seed);
    snprintf(texts[4], 160, "%d", j->max_depth);
    snprintf(texts[5], 160, "worker %s", WORKER_VERSION);
    const struct img_attr list[] = {{"job", j->name},           {"scene", texts[0]}, {"sampler", texts[1]},
                                    {"lightSampler", texts[2]}, {"seed", texts[3]},  {"maxDepth", texts[4]},
                                    {"software", texts[5]}};
    memcpy(a, list, sizeof list);
    return sizeof list / sizeof *list;
}

/* Score the framebuffer fb (its 8-bit conversion img when the reference holds 8-bit display
   values) against ref into rr. 0 or -1 with e filled. */
static int score(const struct rgbf *fb, const struct rgb8 *img, const struct rgbf *ref,
                 enum img_domain domain, struct run_result *rr, struct err *e)
{
    struct rgbf disp = {0};
    int rc = domain == IMG_LINEAR                   ? metrics_compare_f(ref, fb, 1, &rr->error, e)
             : image_f_from_rgb8(img, &disp, e) < 0 ? -1
                                                    : metrics_compare_f(ref, &disp, 1, &rr->error, e);
    image_f_free(&disp);
    rr->has_error = rc == 0;
    rr->error_domain = domain;
    return rc;
}

int run_out_write(const struct job *j, const struct run_opts *o, const float *rgb, int w, int h,
                  const struct procs_result *fr, const struct rgbf *ref, enum img_domain ref_domain,
                  int parts, struct run_result *rr, struct err *e)
{
    char dir[2048], staged[3][2100], attr_text[6][160];
    const char *final[3];
    struct img_attr attrs[8];
    struct rgb8 img = {0};
    struct rgbf fb = {w, h, (float *)rgb};
    char *json = NULL;
    int rc = -1, made_dir = 0, lock = -1, n = 0;
    int is_float = imgio_is_float(j->format), has_ref = ref && ref->px;
    run_paths(j, o->out_dir, dir, rr->image_path, rr->sidecar_path, sizeof rr->image_path);
    run_float_path(j, o->out_dir, rr->float_path, sizeof rr->float_path);
    if (run_out_make_dir(dir, &made_dir, e) < 0 ||
        ((!is_float || (has_ref && ref_domain == IMG_DISPLAY8)) && image_alloc(&img, w, h, e) < 0))
        goto done;
    final[n++] = rr->image_path;
    if (rr->float_path[0])
        final[n++] = rr->float_path;
    final[n++] = rr->sidecar_path;
    for (int i = 0; i < n; i++)
        staged_name(final[i], staged[i], sizeof staged[i]);
    const char *outs[] = {final[0], final[1], n > 2 ? final[2] : NULL, NULL};
    if (run_out_lock_outputs(dir, outs, o, &lock, e) < 0)
        goto done;
    if (img.px)
        image_float_to_rgb8(rgb, w, h, img.px);
    rr->has_error = rr->has_display_error = 0;
    if (has_ref && score(&fb, &img, ref, ref_domain, rr, e) < 0)
        goto done;
    if (o->ref_display && img.px) {
        if (metrics_display_compare(o->ref_display, &img, &rr->display_error, e) < 0)
            goto done;
        rr->has_display_error = 1;
    }
    struct sidecar sc = {j, w, h, fr, rr->has_error ? &rr->error : NULL, ref_domain, j->output, parts};
    if (!(json = sidecar_json(&sc))) {
        err_set(e, NULL, 0, 0, "out of memory writing the sidecar");
        goto done;
    }
    /* All are written whole under staging names first: a failure before the renames (a full disk,
       a size limit) leaves the earlier outputs as they were. Then the earlier sidecar goes, the
       image and its float copy are renamed, the sidecar last: a reader (or a writer killed at any
       step) sees the earlier outputs, images without a sidecar (not finished: rendered again), or
       the new ones, never a new image beside an earlier sidecar (issue 21, defect 6). A killed
       writer's staged files and their temporaries go under the next one's lock. */
    size_t nattrs = exr_attrs(j, attrs, attr_text);
    int k = 0, wrote = is_float ? imgio_write_f(staged[0], &fb, j->format, attrs, nattrs, e)
                                : imgio_write(staged[0], &img, j->format, e);
    if (wrote == 0 && n == 3) /* the float copy */
        wrote = imgio_write_f(staged[++k], &fb, IMG_EXR, attrs, nattrs, e);
    if (wrote == 0)
        wrote = fileio_write_atomic(staged[++k], json, strlen(json), e);
    if (wrote < 0) {
        name_final(e, staged[k], final[k]);
        while (k-- > 0)
            unlink(staged[k]);
        goto done;
    }
    /* a writer stopped (SIGSTOP) until its claim was taken over renames nothing, lock or not */
    int failed = run_out_still_held(o, dir, e) < 0;
    if (!failed && unlink(rr->sidecar_path) < 0 && errno != ENOENT)
        failed = err_set(e, NULL, 0, 0, "cannot write %s: %s", rr->sidecar_path, strerror(errno)) < 0;
    for (int i = 0; i < n; i++) {
        /* a claim taken over between renames: what is renamed stays, without a sidecar */
        if (failed || (i > 0 && run_out_still_held(o, dir, e) < 0)) {
            for (int r = i; r < n; r++)
                unlink(staged[r]);
            goto done;
        }
        if (rename(staged[i], final[i]) == 0)
            continue;
        /* an image without its sidecar is not a finished job: undo the renames done */
        err_set(e, NULL, 0, 0, "cannot write %s: %s", final[i], strerror(errno));
        for (int r = 0; r < n; r++)
            unlink(r < i ? final[r] : staged[r]);
        goto done;
    }
    rr->black = image_float_black(rgb, w, h);
    rc = 0;
done:
    run_out_unlock(lock);
    if (rc != 0 && made_dir)
        rmdir(dir); /* a failed write leaves no empty folder of ours (it fails when not empty) */
    free(json);
    image_free(&img);
    return rc;
}
