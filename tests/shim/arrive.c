/* arrive: an LD_PRELOAD shim for the queue tests that widens the window between a worker's check
   that DIR/X.yaml is free and its move of a claim back to DIR/X.yaml: just before the first such
   move (rename, renameat2 or link from .../running/X.yaml to a path outside running/), it copies
   the file $SHIM_ARRIVE to the destination, as if a user had queued a new X.yaml that instant. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int arrived;

static void arrive(const char *from, const char *to)
{
    const char *src = getenv("SHIM_ARRIVE");
    size_t n = strlen(to);
    if (arrived || !src || !strstr(from, "/running/") || strstr(to, "/running/") || strstr(to, "/done/") ||
        strstr(to, "/failed/") || n < 5 || strcmp(to + n - 5, ".yaml") != 0)
        return;
    arrived = 1;
    FILE *in = fopen(src, "rb"), *out = fopen(to, "wbx");
    int c;
    while (in && out && (c = fgetc(in)) != EOF)
        fputc(c, out);
    if (in)
        fclose(in);
    if (out)
        fclose(out);
}

int rename(const char *from, const char *to)
{
    static int (*real)(const char *, const char *);
    if (!real)
        real = (int (*)(const char *, const char *))dlsym(RTLD_NEXT, "rename");
    arrive(from, to);
    return real(from, to);
}

int renameat2(int fromfd, const char *from, int tofd, const char *to, unsigned flags)
{
    static int (*real)(int, const char *, int, const char *, unsigned);
    if (!real)
        real = (int (*)(int, const char *, int, const char *, unsigned))dlsym(RTLD_NEXT, "renameat2");
    arrive(from, to);
    return real(fromfd, from, tofd, to, flags);
}

int link(const char *from, const char *to)
{
    static int (*real)(const char *, const char *);
    if (!real)
        real = (int (*)(const char *, const char *))dlsym(RTLD_NEXT, "link");
    arrive(from, to);
    return real(from, to);
}
