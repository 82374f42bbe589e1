/* lease: the lease file beside each queue claim, its refresh, and the staleness rules. */
#include "lease.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "base/clock.h"
#include "base/fileio.h"

static double seconds(const struct timespec *t)
{
    return t->tv_sec + t->tv_nsec * 1e-9;
}

/* This process's pid space into out: the boot id (one per kernel boot, so per machine) and the pid
   namespace (one per container); "" where /proc does not say (not Linux). */
static void pid_space(char *out, size_t n)
{
    char boot[64] = "", ns[64] = "";
    FILE *f = fopen("/proc/sys/kernel/random/boot_id", "r");
    if (f) {
        if (!fgets(boot, sizeof boot, f))
            boot[0] = 0;
        fclose(f);
    }
    boot[strcspn(boot, "\n")] = 0;
    ssize_t len = readlink("/proc/self/ns/pid", ns, sizeof ns - 1);
    ns[len > 0 ? len : 0] = 0;
    if (boot[0] && ns[0])
        snprintf(out, n, "%s:%s", boot, ns);
    else
        out[0] = 0;
    for (char *c = out; *c; c++) /* one word per line in the lease file */
        if (*c == ' ' || *c == '\n')
            *c = '_';
}

void lease_init(struct lease *l)
{
    memset(l, 0, sizeof *l);
    if (gethostname(l->host, sizeof l->host - 1) < 0 || !l->host[0])
        snprintf(l->host, sizeof l->host, "localhost");
    for (char *c = l->host; *c; c++) /* one word per line in the lease file */
        if (*c == ' ' || *c == '\n')
            *c = '_';
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    l->pid = (long)getpid();
    pid_space(l->pids, sizeof l->pids);
    l->start = (long long)ts.tv_sec;
    snprintf(l->token, sizeof l->token, "%s:%ld:%lld%09ld", l->host, l->pid, (long long)ts.tv_sec,
             ts.tv_nsec);
}

/* The fixed-width progress line (LEASE_PROGRESS_LEN bytes with its newline) into out. */
static int progress_line(char *out, size_t n, int rows_done, int rows, double render_s, int attempt,
                         int processes)
{
    if (render_s < 0 || render_s > 9e9)
        render_s = 0;
    return snprintf(out, n, "progress %10d %10d %12.1f %5d %5d\n", rows_done, rows, render_s, attempt,
                    processes);
}

void lease_progress(int fd, int rows_done, int rows, double render_s, int attempt, int processes)
{
    char line[LEASE_PROGRESS_LEN + 1];
    struct stat st;
    if (progress_line(line, sizeof line, rows_done, rows, render_s, attempt, processes) !=
            LEASE_PROGRESS_LEN ||
        fstat(fd, &st) < 0 || st.st_size < LEASE_PROGRESS_LEN)
        return;
    (void)pwrite(fd, line, LEASE_PROGRESS_LEN, st.st_size - LEASE_PROGRESS_LEN);
}

int lease_write(const char *claim, const struct lease *l, struct err *e)
{
    char path[2048], text[1024];
    snprintf(path, sizeof path, "%s.lease", claim);
    int n = snprintf(text, sizeof text, "host %s\npid %ld\nstart %lld\ntoken %s\n", l->host, l->pid, l->start,
                     l->token);
    if (l->pids[0]) /* optional: leases of earlier versions lack it */
        n += snprintf(text + n, sizeof text - n, "pids %s\n", l->pids);
    n += progress_line(text + n, sizeof text - n, l->rows_done, l->rows, l->render_s, l->attempt,
                       l->processes);
    return fileio_write_atomic(path, text, (size_t)n, e);
}

/* Printable ASCII only: a lease's words are shown on terminals (status), so escapes become '?'. */
static void printable(char *s)
{
    for (; *s; s++)
        if ((unsigned char)*s < 0x21 || (unsigned char)*s > 0x7e)
            *s = '?';
}

/* A lease's numbers within what a live worker writes; anything else is shown as unknown (0). */
static void sane(struct lease *l)
{
    printable(l->host);
    printable(l->token);
    printable(l->pids);
    if (l->rows < 0 || l->rows > LEASE_MAX_ROWS)
        l->rows = 0;
    if (l->rows_done < 0 || l->rows_done > l->rows)
        l->rows_done = 0;
    if (!(l->render_s >= 0 && l->render_s <= 1e10))
        l->render_s = 0;
    if (l->attempt < 0 || l->attempt > 1000)
        l->attempt = 0;
    if (l->processes < 0 || l->processes > 4096)
        l->processes = 0;
    if (l->start < 0 || (double)l->start > clock_s(CLOCK_REALTIME) + 86400.0)
        l->start = 0;
}

/* Read the lease-format file claim + suffix (a lease, or a recovery lock naming its holder). */
static int read_side(const char *claim, const char *suffix, struct lease *l, double *age_s)
{
    char path[2048], text[LEASE_MAX_BYTES + 1];
    snprintf(path, sizeof path, "%s%s", claim, suffix);
    memset(l, 0, sizeof *l);
    /* never blocks (a FIFO), never follows a link (to /dev/zero), never reads more than a lease holds */
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (fd < 0)
        return -1;
    struct stat st;
    ssize_t n = 0;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size <= LEASE_MAX_BYTES)
        n = read(fd, text, LEASE_MAX_BYTES);
    close(fd);
    if (n <= 0)
        return -1;
    text[n] = 0;
    int fields = 0;
    for (char *line = text, *next; line && *line; line = next) { /* a blank line ends it, as written */
        next = strchr(line, '\n');
        if (next)
            *next++ = 0;
        fields += sscanf(line, "host %255s", l->host) == 1;
        fields += sscanf(line, "pid %ld", &l->pid) == 1;
        fields += sscanf(line, "start %lld", &l->start) == 1;
        fields += sscanf(line, "token %383s", l->token) == 1;
        (void)sscanf(line, "pids %127s", l->pids);
        (void)sscanf(line, "broke %d", &l->broke);
        (void)sscanf(line, "progress %d %d %lf %d %d", &l->rows_done, &l->rows, &l->render_s, &l->attempt,
                     &l->processes);
    }
    if (fields != 4)
        return -1;
    sane(l);
    *age_s = clock_s(CLOCK_REALTIME) - seconds(&st.st_mtim);
    return 0;
}

int lease_read(const char *claim, struct lease *l, double *age_s)
{
    return read_side(claim, ".lease", l, age_s);
}

/* 1 when the process l names runs in this pid space and is gone (or names nobody). */
static int holder_gone(const struct lease *l)
{
    struct lease me;
    lease_init(&me);
    /* The pid is only ours to ask kill() about in our pid space: a worker in a container that
       shares this hostname (host networking) has pids we cannot see, and is judged by its lease's
       age as another host's is. A lease that does not say (an earlier version) is taken as ours. */
    int same_space = !strcmp(l->host, me.host) && (!l->pids[0] || !me.pids[0] || !strcmp(l->pids, me.pids));
    /* pid 0 or -1 would ask kill() about whole process groups: such a lease names nobody */
    return same_space && (l->pid <= 0 || l->pid == me.pid || (kill((pid_t)l->pid, 0) < 0 && errno == ESRCH));
}

/* 1 when the claim's recovery lock, made since the claim was (claimed_s: its ctime), names a holder
   of this host that is gone (a worker killed while it filed or returned the claim: it removes the
   lease first, under the lock), or is our own, taken from such a holder. */
static int lock_holder_gone(const char *claim, double claimed_s, struct lease *l)
{
    char path[2048];
    struct stat st;
    double age;
    snprintf(path, sizeof path, "%s.lock", claim);
    if (lstat(path, &st) < 0 || seconds(&st.st_mtim) < claimed_s || read_side(claim, ".lock", l, &age) < 0)
        return 0; /* a lock older than the claim is an earlier claim's, left behind */
    return l->pid == (long)getpid() ? l->broke : holder_gone(l);
}

void lease_touch(const char *claim)
{
    char path[2048];
    snprintf(path, sizeof path, "%s.lease", claim);
    (void)utimensat(AT_FDCWD, path, NULL, 0);
}

void lease_remove(const char *claim)
{
    char path[2048];
    snprintf(path, sizeof path, "%s.lease", claim);
    unlink(path);
}

int lease_stale(const char *claim, double timeout_s, char *why, size_t n)
{
    struct stat cst;
    if (stat(claim, &cst) < 0)
        return 0;
    struct lease l;
    double age;
    if (lease_read(claim, &l, &age) < 0) {
        if (lock_holder_gone(claim, seconds(&cst.st_ctim), &l)) {
            snprintf(
                why, n,
                "its worker is gone, killed while it filed the claim (no lease; its lock's holder gone)");
            return 1;
        }
        /* rename() sets the claim's ctime: the time it was claimed */
        double claimed = clock_s(CLOCK_REALTIME) - seconds(&cst.st_ctim);
        snprintf(why, n, "claimed %.0f s ago and no lease was written", claimed);
        return claimed > timeout_s;
    }
    if (holder_gone(&l)) {
        snprintf(why, n, "its worker (pid %ld on %s) is gone", l.pid, l.host);
        return 1;
    }
    snprintf(why, n, "its worker (pid %ld on %s) has not renewed the lease for %.0f s", l.pid, l.host, age);
    return age > timeout_s;
}

int lease_lock(const char *claim, double timeout_s)
{
    char path[2048], text[1024];
    struct stat cst;
    double claimed_s = stat(claim, &cst) == 0 ? seconds(&cst.st_ctim) : 0;
    int broke = 0;
    snprintf(path, sizeof path, "%s.lock", claim);
    for (int attempt = 0; attempt < 2; attempt++) {
        int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
        if (fd >= 0) { /* it names its holder, as a lease does, so that its holder's death is seen at once */
            struct lease me;
            lease_init(&me);
            int len =
                snprintf(text, sizeof text, "host %s\npid %ld\nstart %lld\ntoken %s\npids %s\nbroke %d\n",
                         me.host, me.pid, me.start, me.token, me.pids, broke);
            (void)!write(fd, text, (size_t)len);
            close(fd);
            return 0;
        }
        struct stat st;
        struct lease l;
        if (errno != EEXIST || stat(path, &st) < 0)
            break;
        broke = lock_holder_gone(claim, claimed_s, &l);
        if (!broke && !(clock_s(CLOCK_REALTIME) - seconds(&st.st_mtim) > timeout_s))
            break;
        unlink(path); /* its holder died mid-recovery or mid-filing: broken, and tried once more */
    }
    return -1;
}

void lease_sweep_locks(const char *running, const char *name, double timeout_s)
{
    char claim[2048], path[2100];
    struct stat st;
    struct lease l;
    size_t len = strlen(name);
    if (len < 11 || strcmp(name + len - 5, ".lock") || name[0] == '.')
        return;
    snprintf(claim, sizeof claim, "%s/%.*s", running, (int)(len - 5), name);
    snprintf(path, sizeof path, "%s/%s", running, name);
    if (lstat(claim, &st) == 0 || lstat(path, &st) < 0 || !S_ISREG(st.st_mode))
        return;
    if (clock_s(CLOCK_REALTIME) - seconds(&st.st_mtim) > timeout_s || lock_holder_gone(claim, 0, &l))
        unlink(path);
}

void lease_unlock(const char *claim)
{
    char path[2048];
    snprintf(path, sizeof path, "%s.lock", claim);
    unlink(path);
}
