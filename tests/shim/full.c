/* full: an LD_PRELOAD shim for the tests of a full disk: write() to a regular file under the folder
   $SHIM_FULL (an absolute path), and rename() to a path under it, fail with ENOSPC. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Whether path lies under $SHIM_FULL. */
static int under_full(const char *path)
{
    const char *dir = getenv("SHIM_FULL");
    size_t n = dir ? strlen(dir) : 0;
    return n > 0 && strncmp(path, dir, n) == 0 && (path[n] == '/' || path[n] == 0);
}

ssize_t write(int fd, const void *buf, size_t len)
{
    static ssize_t (*real)(int, const void *, size_t);
    if (!real)
        real = (ssize_t(*)(int, const void *, size_t))dlsym(RTLD_NEXT, "write");
    char link[64], path[4096];
    struct stat st;
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    ssize_t k =
        fd > 2 && fstat(fd, &st) == 0 && S_ISREG(st.st_mode) ? readlink(link, path, sizeof path - 1) : -1;
    if (k > 0) {
        path[k] = 0;
        if (under_full(path)) {
            errno = ENOSPC;
            return -1;
        }
    }
    return real(fd, buf, len);
}

int rename(const char *from, const char *to)
{
    static int (*real)(const char *, const char *);
    if (!real)
        real = (int (*)(const char *, const char *))dlsym(RTLD_NEXT, "rename");
    if (to[0] == '/' && under_full(to)) {
        errno = ENOSPC;
        return -1;
    }
    return real(from, to);
}
