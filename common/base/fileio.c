/* fileio: bounded whole-file reads and atomic writes (temporary file + rename). */
#define _GNU_SOURCE /* renameat2 */
#include "fileio.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hash.h"

#define FILEIO_CHUNK ((size_t)1 << 30) /* largest single read()/write() we ask for */

/* Read up to size bytes from fd into buf, retrying on EINTR; stops early at end of file. */
static int read_full(int fd, uint8_t *buf, size_t size, size_t *got)
{
    *got = 0;
    while (*got < size) {
        size_t want = size - *got < FILEIO_CHUNK ? size - *got : FILEIO_CHUNK;
        ssize_t r = read(fd, buf + *got, want);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            return -1;
        if (r == 0)
            break;
        *got += (size_t)r;
    }
    return 0;
}

/* The kind of a file system entry that is not a regular file, from its mode. */
static const char *mode_kind(mode_t m)
{
    return S_ISREG(m)    ? "a regular file"
           : S_ISDIR(m)  ? "a directory"
           : S_ISFIFO(m) ? "a FIFO"
           : S_ISCHR(m)  ? "a character device"
           : S_ISBLK(m)  ? "a block device"
           : S_ISSOCK(m) ? "a socket"
                         : "not a regular file";
}

int fileio_read_all(const char *path, size_t max_bytes, uint8_t **data, size_t *len, struct err *e)
{
    *data = NULL;
    *len = 0;
    /* O_NONBLOCK so that opening a FIFO cannot hang; fstat rejects it just below */
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0)
        return err_set(e, path, 0, 0, "%s", strerror(errno));
    struct stat st;
    uint8_t *buf = NULL;
    size_t got = 0;
    if (fstat(fd, &st) < 0) {
        err_set(e, path, 0, 0, "%s", strerror(errno));
        goto fail;
    }
    if (S_ISDIR(st.st_mode)) {
        err_set(e, path, 0, 0, "%s", strerror(EISDIR));
        goto fail;
    }
    if (!S_ISREG(st.st_mode)) {
        err_set(e, path, 0, 0, "is %s, not a regular file", mode_kind(st.st_mode));
        goto fail;
    }
    if (st.st_size < 0 || (uintmax_t)st.st_size > max_bytes || (uintmax_t)st.st_size >= SIZE_MAX) {
        err_set(e, path, 0, 0, "file too large (%jd bytes, limit %zu)", (intmax_t)st.st_size, max_bytes);
        goto fail;
    }
    buf = malloc((size_t)st.st_size + 1);
    if (!buf) {
        err_set(e, path, 0, 0, "out of memory reading %jd bytes", (intmax_t)st.st_size);
        goto fail;
    }
    if (read_full(fd, buf, (size_t)st.st_size, &got) < 0) {
        err_set(e, path, 0, 0, "read error: %s", strerror(errno));
        goto fail;
    }
    close(fd);
    buf[got] = '\0';
    *data = buf;
    *len = got;
    return 0;
fail:
    free(buf);
    close(fd);
    return -1;
}

/* Write all len bytes, continuing after short writes and EINTR. */
static int write_full(int fd, const uint8_t *p, size_t len)
{
    while (len > 0) {
        ssize_t w = write(fd, p, len < FILEIO_CHUNK ? len : FILEIO_CHUNK);
        if (w < 0 && errno == EINTR)
            continue;
        if (w < 0)
            return -1;
        if (w == 0) {
            errno = ENOSPC; /* no progress and no error: treat as a full device */
            return -1;
        }
        p += w;
        len -= (size_t)w;
    }
    return 0;
}

/* Length of path's directory part including its last '/', or 0 when there is none. */
static size_t dir_len(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? (size_t)(slash - path) + 1 : 0;
}

/* Make the rename durable by syncing the directory; best effort, errors are ignored. */
static void sync_dir(const char *path, size_t dlen)
{
    char *dir = dlen ? strndup(path, dlen) : strdup(".");
    if (!dir)
        return;
    int fd = open(dir, O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
        (void)fsync(fd);
        close(fd);
    }
    free(dir);
}

int fileio_hash(const char *path, size_t max_bytes, uint64_t *h, struct err *e)
{
    uint8_t *data;
    size_t len;
    if (fileio_read_all(path, max_bytes, &data, &len, e) < 0)
        return -1;
    *h = hash_bytes(*h, data, len);
    free(data);
    return 0;
}

/* Mode 0644, written whole, fsynced and closed before it counts. */
int fileio_stage(const char *path, const void *data, size_t len, char *staged, size_t n, struct err *e)
{
    size_t dlen = dir_len(path);
    const char *base = path + dlen;
    if (!*base)
        return err_set(e, NULL, 0, 0, "cannot write %s: %s", path, strerror(EISDIR));
    if ((size_t)snprintf(staged, n, "%.*s.%s.tmp.XXXXXX", (int)dlen, path, base) >= n)
        return err_set(e, NULL, 0, 0, "cannot write %s: %s", path, strerror(ENAMETOOLONG));
    int fd = mkstemp(staged);
    if (fd < 0)
        return err_set_errno(e, errno, "cannot write %s: %s", path, strerror(errno));
    if (fchmod(fd, 0644) < 0 || write_full(fd, data, len) < 0 || fsync(fd) < 0)
        goto fail;
    int closing = fd;
    fd = -1;
    if (close(closing) < 0)
        goto fail;
    return 0;
fail:
    err_set_errno(e, errno, "cannot write %s: %s", path, strerror(errno));
    if (fd >= 0)
        close(fd);
    unlink(staged);
    return -1;
}

int fileio_commit(const char *staged, const char *path, struct err *e)
{
    if (rename(staged, path) < 0) {
        err_set_errno(e, errno, "cannot write %s: %s", path, strerror(errno));
        unlink(staged);
        return -1;
    }
    sync_dir(path, dir_len(path));
    return 0;
}

int fileio_write_atomic(const char *path, const void *data, size_t len, struct err *e)
{
    size_t n = strlen(path) + sizeof "..tmp.XXXXXX";
    char *staged = malloc(n);
    if (!staged)
        return err_set(e, NULL, 0, 0, "cannot write %s: out of memory", path);
    int rc = fileio_stage(path, data, len, staged, n, e) < 0 ? -1 : fileio_commit(staged, path, e);
    free(staged);
    return rc;
}

int fileio_write_text(const char *dir, const char *file, char *text, struct err *e)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    if (!text)
        return e->msg[0] ? -1 : err_set(e, NULL, 0, 0, "out of memory writing %s", path);
    int rc = fileio_write_atomic(path, text, strlen(text), e);
    free(text);
    return rc;
}

const char *fileio_kind(const char *path)
{
    static const char *const linked[] = {"a symbolic link to a directory", "a symbolic link to a FIFO",
                                         "a symbolic link to a character device",
                                         "a symbolic link to a block device", "a symbolic link to a socket"};
    struct stat st, lst;
    if (lstat(path, &lst) < 0)
        return NULL;
    if (stat(path, &st) < 0)
        return errno == ELOOP ? "a symbolic link that loops" : "a symbolic link to nothing";
    const char *kind = mode_kind(st.st_mode);
    if (!S_ISLNK(lst.st_mode) || S_ISREG(st.st_mode))
        return kind;
    for (size_t i = 0; i < sizeof linked / sizeof linked[0]; i++)
        if (!strcmp(linked[i] + strlen("a symbolic link to "), kind))
            return linked[i];
    return "a symbolic link to something not a regular file";
}

int fileio_output_ok(const char *path, const char *const *inputs, size_t n, struct err *e)
{
    struct stat st, in;
    if (lstat(path, &st) < 0)
        return errno == ENOENT ? 0 : err_set(e, NULL, 0, 0, "%s: %s", path, strerror(errno));
    const char *what = S_ISLNK(st.st_mode)                          ? "a symbolic link"
                       : S_ISDIR(st.st_mode)                        ? "a folder"
                       : S_ISFIFO(st.st_mode)                       ? "a FIFO"
                       : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                       : !S_ISREG(st.st_mode)                       ? "not a regular file"
                                                                    : NULL;
    if (what)
        return err_set(e, NULL, 0, 0, "%s: is %s, not replaced (only a new or a regular file is written)",
                       path, what);
    for (size_t i = 0; i < n; i++)
        if (inputs[i] && stat(inputs[i], &in) == 0 && in.st_dev == st.st_dev && in.st_ino == st.st_ino)
            return err_set(e, NULL, 0, 0, "%s: is the input %s, not replaced", path, inputs[i]);
    return 0;
}

int fileio_rename_noreplace(const char *from, const char *to)
{
    if (renameat2(AT_FDCWD, from, AT_FDCWD, to, RENAME_NOREPLACE) == 0)
        return 0;
    if (errno != EINVAL && errno != ENOSYS) /* EEXIST, ENOENT, ...: the answer */
        return -1;
    /* a file system without RENAME_NOREPLACE: link() refuses an existing name just as well */
    if (link(from, to) < 0)
        return -1;
    if (unlink(from) < 0) {
        int saved = errno;
        unlink(to);
        errno = saved;
        return -1;
    }
    return 0;
}
