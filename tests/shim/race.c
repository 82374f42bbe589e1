/* race: an LD_PRELOAD shim for the queue tests that widens a race window around one rename(),
   chosen by the environment, so that a test hits it every time:
   SHIM_KILL_TO=SUFFIX   a staged file (a name holding ".tmp.") renamed to a path ending in SUFFIX:
                         the process kills itself (SIGKILL) just before that rename;
   SHIM_KILL_BEFORE=SUFFIX, SHIM_KILL_AFTER=SUFFIX
                         the first rename (of anything) to a path ending in SUFFIX: the process
                         kills itself (SIGKILL) just before, or just after, that rename;
   SHIM_STOP_TO=TEXT     the first rename to a path containing TEXT: the process stops itself
                         (SIGSTOP) just before it, until a SIGCONT;
   SHIM_STOP_STAGE=TEXT  the first temporary file made (mkstemp) whose name contains TEXT: the
                         process stops itself just before making it (an output being staged);
   SHIM_REQUEUE=LEASE    the first claim filed (.../running/X.yaml renamed out of running/): just
                         after, another worker claims a re-queued X.yaml, as if it had been that
                         quick: running/X.yaml appears again, with the lease file LEASE copied
                         beside it. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int stopped, requeued;

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && !strcmp(s + n - k, suffix);
}

static void copy(const char *src, const char *dst)
{
    FILE *in = fopen(src, "rb"), *out = in ? fopen(dst, "wbx") : NULL;
    int c;
    while (out && (c = fgetc(in)) != EOF)
        fputc(c, out);
    if (in)
        fclose(in);
    if (out)
        fclose(out);
}

static void before(const char *from, const char *to)
{
    const char *kill_to = getenv("SHIM_KILL_TO"), *stop_to = getenv("SHIM_STOP_TO");
    const char *kill_before = getenv("SHIM_KILL_BEFORE");
    if (kill_to && strstr(from, ".tmp.") && ends_with(to, kill_to))
        raise(SIGKILL);
    if (kill_before && ends_with(to, kill_before))
        raise(SIGKILL);
    if (stop_to && !stopped && strstr(to, stop_to)) {
        stopped = 1;
        raise(SIGSTOP);
    }
}

static void after(const char *from, const char *to, int rc)
{
    const char *lease = getenv("SHIM_REQUEUE"), *kill_after = getenv("SHIM_KILL_AFTER");
    char path[4096];
    if (rc == 0 && kill_after && ends_with(to, kill_after))
        raise(SIGKILL);
    if (rc != 0 || !lease || requeued || !strstr(from, "/running/") || strstr(to, "/running/") ||
        !ends_with(from, ".yaml"))
        return;
    requeued = 1;
    copy(to, from);
    snprintf(path, sizeof path, "%s.lease", from);
    copy(lease, path);
}

int rename(const char *from, const char *to)
{
    static int (*real)(const char *, const char *);
    if (!real)
        real = (int (*)(const char *, const char *))dlsym(RTLD_NEXT, "rename");
    before(from, to);
    int rc = real(from, to);
    after(from, to, rc);
    return rc;
}

int renameat2(int fromfd, const char *from, int tofd, const char *to, unsigned flags)
{
    static int (*real)(int, const char *, int, const char *, unsigned);
    if (!real)
        real = (int (*)(int, const char *, int, const char *, unsigned))dlsym(RTLD_NEXT, "renameat2");
    before(from, to);
    int rc = real(fromfd, from, tofd, to, flags);
    after(from, to, rc);
    return rc;
}

int mkstemp(char *template)
{
    static int (*real)(char *);
    const char *stop_stage = getenv("SHIM_STOP_STAGE");
    if (!real)
        real = (int (*)(char *))dlsym(RTLD_NEXT, "mkstemp");
    if (stop_stage && !stopped && strstr(template, stop_stage)) {
        stopped = 1;
        raise(SIGSTOP);
    }
    return real(template);
}
