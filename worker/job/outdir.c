/* outdir: the names of a job's outputs, its folder made, checked and locked. */
#include "outdir.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "base/clock.h"
#include "image/imgio.h"

const char *outdir_root(const char *out_dir)
{
    return out_dir ? out_dir : OUTDIR_DEFAULT;
}

void outdir_stem(const char *path, char *out, size_t n)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    int len = dot && dot != base ? (int)(dot - base) : (int)strlen(base);
    snprintf(out, n, "%.*s", len, base);
}

void outdir_dir(const char *out_dir, const char *name, char *buf, size_t n)
{
    snprintf(buf, n, "%s/%s", outdir_root(out_dir), name);
}

void outdir_files(const struct job *j, const char *out_dir, struct outdir_files *f)
{
    char stem[JOB_NAME_MAX], dir[sizeof f->dir];
    int has_float = imgio_is_float(j->format);
    outdir_stem(j->output, stem, sizeof stem);
    outdir_dir(out_dir, j->name, dir, sizeof dir);
    snprintf(f->dir, sizeof f->dir, "%s", dir);
    snprintf(f->image[0], sizeof f->image[0], "%s/%s", dir, j->output);
    f->format[0] = j->format;
    f->n_images = 1;
    for (int i = 0; i < j->n_more; i++, f->n_images++) {
        snprintf(f->image[f->n_images], sizeof f->image[0], "%s/%s", dir, j->more_output[i]);
        f->format[f->n_images] = j->more_format[i];
        has_float |= imgio_is_float(j->more_format[i]);
    }
    f->float_copy = -1;
    if (j->float_copy && !has_float) {
        f->float_copy = f->n_images++;
        snprintf(f->image[f->float_copy], sizeof f->image[0], "%s/%s.exr", dir, stem);
        f->format[f->float_copy] = IMG_EXR;
    }
    snprintf(f->sidecar, sizeof f->sidecar, "%s/%s.json", dir, stem);
}

void outdir_part_files(const struct job *j, const char *out_dir, int part, int parts, struct outdir_files *f)
{
    outdir_dir(out_dir, j->name, f->dir, sizeof f->dir);
    outdir_part_path(j, out_dir, part, parts, f->image[0], sizeof f->image[0]);
    f->format[0] = j->format;
    f->n_images = 1;
    f->float_copy = -1;
    f->sidecar[0] = 0;
}

void outdir_part_path(const struct job *j, const char *out_dir, int part, int parts, char *buf, size_t n)
{
    char stem[JOB_NAME_MAX];
    outdir_stem(j->output, stem, sizeof stem);
    snprintf(buf, n, "%s/%s/%s.part-%d-of-%d", outdir_root(out_dir), j->name, stem, part, parts);
}

int outdir_part_name(const struct job *j, const char *file, int *part, int *parts)
{
    char stem[JOB_NAME_MAX], prefix[JOB_NAME_MAX + 8];
    outdir_stem(j->output, stem, sizeof stem);
    snprintf(prefix, sizeof prefix, "%s.part-", stem);
    size_t pl = strlen(prefix);
    int end = 0;
    return strncmp(file, prefix, pl) == 0 && sscanf(file + pl, "%d-of-%d%n", part, parts, &end) == 2 &&
           file[pl + end] == 0;
}

int outdir_check(const char *dir, struct err *e)
{
    char p[2048];
    snprintf(p, sizeof p, "%s", dir);
    for (;;) {
        struct stat st;
        if (stat(p, &st) == 0) {
            if (!S_ISDIR(st.st_mode))
                return err_set_errno(e, ENOTDIR, "cannot create directory %s: a file is in the way", p);
            if (access(p, W_OK | X_OK) < 0)
                return err_set_errno(e, errno, "cannot write to output directory %s: %s", p, strerror(errno));
            return 0;
        }
        if ((errno != ENOENT && errno != ENOTDIR) || !strcmp(p, "."))
            return err_set_errno(e, errno, "cannot create directory %s: %s", dir, strerror(errno));
        /* missing, but a name is there: a dangling symbolic link, where mkdir fails (EEXIST) */
        if (lstat(p, &st) == 0)
            return err_set_errno(e, ENOTDIR, "cannot create directory %s: a file is in the way (%s)", p,
                                 S_ISLNK(st.st_mode) ? "a symbolic link to nothing" : "not a directory");
        char *slash = strrchr(p, '/');
        if (!slash)
            snprintf(p, sizeof p, ".");
        else
            slash[slash == p] = '\0'; /* "/x" -> "/", "a/b" -> "a" */
    }
}

int outdir_env_error(const struct err *e)
{
    int n = e->errnum;
    return n == EACCES || n == EPERM || n == EROFS || n == ENOSPC || n == EDQUOT;
}

int outdir_mkdirs(const char *path, int *made, struct err *e)
{
    char buf[2048];
    snprintf(buf, sizeof buf, "%s", path);
    if (made)
        *made = 0;
    for (char *p = buf + 1;; p++) {
        if (*p != '/' && *p != 0)
            continue;
        char c = *p;
        *p = 0;
        int ok = mkdir(buf, 0755) == 0;
        if (!ok && errno != EEXIST)
            return err_set_errno(e, errno, "cannot create directory %s: %s", buf, strerror(errno));
        struct stat st;
        /* the folder itself is never a symbolic link: outputs would land wherever it points */
        if (!c && lstat(buf, &st) == 0 && S_ISLNK(st.st_mode))
            return err_set_errno(
                e, ELOOP, "%s is a symbolic link: outputs are never written through one (make it a folder)",
                buf);
        if (stat(buf, &st) < 0 || !S_ISDIR(st.st_mode))
            return err_set_errno(e, ENOTDIR, "cannot create directory %s: a file is in the way", buf);
        *p = c;
        if (!c) {
            if (made)
                *made = ok;
            return 0;
        }
    }
}

/* Whether n is a temporary of the file named base: fileio_stage's ".<base>.tmp.XXXXXX", or what
   writers before issue 29 left, which staged twice: "..<base>.tmp.XXXXXX.tmp.YYYYYY". */
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

/* Whether n is any writer's temporary (is_temp_of, whatever the file): ".<base>.tmp.XXXXXX". */
static int is_temp(const char *n)
{
    size_t len = strlen(n);
    return n[0] == '.' && len > 12 && !strncmp(n + len - 11, ".tmp.", 5);
}

/* Remove, in one pass over the open folder fd, the temporaries that writers killed half-way left:
   for the given paths in it (is_temp_of), or every one when paths is NULL (is_temp). Only the
   holder of the folder's lock may call it. */
static void remove_temps(int fd, const char *const *paths)
{
    DIR *d = fdopendir(dup(fd));
    struct dirent *de;
    while (d && (de = readdir(d))) {
        int dead = !paths && is_temp(de->d_name);
        for (int i = 0; paths && paths[i] && !dead; i++) {
            const char *slash = strrchr(paths[i], '/');
            dead = is_temp_of(de->d_name, slash ? slash + 1 : paths[i]);
        }
        if (dead)
            (void)unlinkat(fd, de->d_name, 0);
    }
    if (d)
        closedir(d);
}

/* flock(fd, LOCK_EX) for at most wait_s seconds (> 0) in 20 ms steps; -1 with errno EWOULDBLOCK
   when waited out, EINTR when *stop was set meanwhile. */
static int lock_within(int fd, double wait_s, const volatile sig_atomic_t *stop)
{
    const struct timespec nap = {0, 20 * 1000 * 1000};
    const double t0 = clock_s(CLOCK_MONOTONIC);
    for (;;) {
        if (flock(fd, LOCK_EX | LOCK_NB) == 0)
            return 0;
        if (errno != EWOULDBLOCK && errno != EINTR)
            return -1;
        if (stop && *stop) {
            errno = EINTR;
            return -1;
        }
        if (clock_s(CLOCK_MONOTONIC) - t0 > wait_s) {
            errno = EWOULDBLOCK;
            return -1;
        }
        nanosleep(&nap, NULL);
    }
}

void outdir_remove_temps(const char *dir)
{
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0)
        return;
    if (lock_within(fd, 1.0, NULL) == 0)
        remove_temps(fd, NULL);
    close(fd); /* and the lock with it */
}

int outdir_lock(const char *dir, const char *const *paths, const volatile sig_atomic_t *stop, double wait_s)
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
        return why == EINTR ? OUTDIR_STOPPED : why == EWOULDBLOCK ? OUTDIR_WAITED_OUT : -1;
    }
    if (paths && paths[0])
        remove_temps(fd, paths);
    return fd;
}

void outdir_unlock(int fd)
{
    if (fd >= 0)
        close(fd); /* closing the last descriptor of the open folder releases the flock */
}
