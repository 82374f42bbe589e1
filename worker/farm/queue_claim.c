/* queue_claim: claim by rename(), lease while rendering, file as done or failed, recover dead claims. */
#include "queue_claim.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

#include "base/clock.h"
#include "base/err.h"
#include "base/fileio.h"
#include "base/json.h"
#include "job/sidecar.h"
#include "queue_log.h"

/* Seconds between lease renewals: one, or a quarter of --lease-timeout when that is shorter. */
static double renew_every_s(const struct queue *q)
{
    return q->o->lease_timeout_s / 4 < 1.0 ? q->o->lease_timeout_s / 4 : 1.0;
}

/* The open lease file the renewal timer touches (-1: none); a signal handler's only way to it. */
static volatile sig_atomic_t renew_fd = -1;

/* The render's progress callback (run_opts.tick, every 5 ms): every renew_every_s, the lease renewed
   with the render's progress while the claim is still ours; a claim gone (cancelled) or taken over
   sets q->lost and *q->stop to QUEUE_STOP_CLAIM_LOST, which stops the render. */
static void tick(void *arg, int rows_done, int rows, double elapsed_s)
{
    struct queue *q = arg;
    if (clock_s(CLOCK_MONOTONIC) - q->last_touch < renew_every_s(q))
        return;
    q->last_touch = clock_s(CLOCK_MONOTONIC);
    if (!queue_claim_still_ours(q)) {
        q->lost = 1;
        if (q->stop && !*q->stop)
            *q->stop = QUEUE_STOP_CLAIM_LOST;
        return;
    }
    if (renew_fd >= 0)
        lease_progress(renew_fd, rows_done, rows, elapsed_s, q->attempt, q->processes);
    else
        lease_touch(q->claim);
}

static void on_renew_alarm(int sig)
{
    (void)sig;
    int saved = errno, fd = renew_fd;
    if (fd >= 0)
        (void)futimens(fd, NULL);
    errno = saved;
}

static void renew_stop(void)
{
    struct itimerval off;
    memset(&off, 0, sizeof off);
    setitimer(ITIMER_REAL, &off, NULL);
    int fd = renew_fd;
    renew_fd = -1;
    if (fd >= 0)
        close(fd);
}

void queue_claim_begin(struct queue *q)
{
    char path[2100];
    q->lost = 0;
    q->processes = 0;
    q->name_owner[0] = 0;
    snprintf(path, sizeof path, "%s.lease", q->claim); /* lease.c's name for the claim's lease */
    renew_stop();
    /* a lease is a regular file: a FIFO or device put in its place must not block or feed us */
    int fd = open(path, O_RDWR | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    struct stat st;
    if (fd >= 0 && (fstat(fd, &st) < 0 || !S_ISREG(st.st_mode))) {
        close(fd);
        fd = -1;
    }
    if (fd < 0)
        return; /* no lease to renew: the tick's check finds the claim lost */
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_renew_alarm;
    sa.sa_flags = SA_RESTART;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGALRM, &sa, NULL);
    renew_fd = fd;
    double every = renew_every_s(q);
    struct itimerval it = {{(time_t)every, (suseconds_t)((every - (time_t)every) * 1e6)},
                           {(time_t)every, (suseconds_t)((every - (time_t)every) * 1e6)}};
    setitimer(ITIMER_REAL, &it, NULL);
}

void queue_claim_end(struct queue *q)
{
    sigset_t block, old;
    renew_stop();
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigprocmask(SIG_BLOCK, &block, &old);
    if (*q->stop == QUEUE_STOP_CLAIM_LOST)
        *q->stop = 0;
    sigprocmask(SIG_SETMASK, &old, NULL);
}

int queue_claim_return(struct queue *q, const char *claim, const char *name)
{
    char back[2048];
    snprintf(back, sizeof back, "%s/%s", q->dir, name);
    /* the lease goes first (see the header), and comes back when a new file took the name */
    struct lease l;
    double age;
    int had = lease_read(claim, &l, &age) == 0;
    lease_remove(claim);
    if (fileio_rename_noreplace(claim, back) == 0)
        return 0;
    int saved = errno;
    struct err e;
    if (had)
        (void)lease_write(claim, &l, &e);
    errno = saved;
    return -1;
}

/* Take the dead claim at `claim` over where it lies, under its recovery lock: our lease replaces
   its holder's and it becomes the claim in hand. 0 when it is ours. */
static int adopt_claim(struct queue *q, const char *claim, const char *name)
{
    struct err e;
    struct stat st;
    if (stat(claim, &st) < 0) /* its holder returned it meanwhile, lock or not */
        return -1;
    snprintf(q->claim, sizeof q->claim, "%s", claim);
    lease_init(&q->lease);
    q->last_touch = clock_s(CLOCK_MONOTONIC);
    if (lease_write(q->claim, &q->lease, &e) == 0)
        return 0;
    char buf[2048];
    err_format(&e, buf, sizeof buf);
    queue_log(name, "%s\n", buf);
    return -1;
}

/* running/.X.yaml.lease.tmp.XXXXXX: the temporary file of a lease write (fileio_write_atomic)
   whose worker was killed before its rename (a worker killed just after claiming leaves one
   most of the time: the write's fsync is the slow part). A live writer renames it within
   moments, so one older than the lease timeout is a dead writer's: removed. */
static void remove_dead_lease_temp(struct queue *q, const char *name)
{
    const char *tmp = strstr(name, ".yaml.lease.tmp.");
    struct stat st;
    char path[2048];
    if (name[0] != '.' || !tmp || strlen(tmp + strlen(".yaml.lease.tmp.")) != 6)
        return;
    snprintf(path, sizeof path, "%s/%s", q->running, name);
    if (lstat(path, &st) == 0 && S_ISREG(st.st_mode) &&
        clock_s(CLOCK_REALTIME) - (st.st_mtim.tv_sec + st.st_mtim.tv_nsec * 1e-9) > q->o->lease_timeout_s)
        unlink(path);
}

int queue_claim_recover(struct queue *q, char *adopted, size_t n)
{
    DIR *d = opendir(q->running);
    int took = 0;
    if (!d)
        return 0;
    struct dirent *de;
    while (!took && (de = readdir(d))) {
        char claim[2048], why[512];
        remove_dead_lease_temp(q, de->d_name);
        lease_sweep_locks(q->running, de->d_name, q->o->lease_timeout_s);
        if (!queue_scan_is_job_file(de->d_name))
            continue;
        snprintf(claim, sizeof claim, "%s/%s", q->running, de->d_name);
        if (!lease_stale(claim, q->o->lease_timeout_s, why, sizeof why) ||
            lease_lock(claim, q->o->lease_timeout_s) < 0)
            continue;
        /* judged again under the lock: another recoverer may have moved it meanwhile */
        if (lease_stale(claim, q->o->lease_timeout_s, why, sizeof why)) {
            int returned =
                !queue_scan_has(q->dir, de->d_name) && queue_claim_return(q, claim, de->d_name) == 0;
            if (returned)
                queue_log(de->d_name, "returned to the queue: %s\n", why);
            /* not returned: a new file of that name waits (or arrived just now) */
            if (!returned && adopt_claim(q, claim, de->d_name) == 0) {
                queue_log(de->d_name, "taken over in %s/ (a newer %s waits in the queue): %s\n", q->running,
                          de->d_name, why);
                snprintf(adopted, n, "%s", de->d_name);
                took = 1;
            }
        }
        lease_unlock(claim);
    }
    closedir(d);
    return took;
}

int queue_claim_take(struct queue *q, const char *name)
{
    char from[2048];
    struct stat st;
    struct err e;
    snprintf(from, sizeof from, "%s/%s", q->dir, name);
    snprintf(q->claim, sizeof q->claim, "%s/%s", q->running, name);
    if (stat(q->claim, &st) == 0) /* a job of the same file name is running: it waits */
        return 1;
    if (rename(from, q->claim) < 0) {
        if (errno == ENOENT) /* another worker was first */
            return 1;
        queue_log(name, "worker: --queue %s: cannot claim %s into %s/: %s", q->dir, name, q->running,
                  strerror(errno));
        return -1;
    }
    lease_init(&q->lease);
    q->last_touch = clock_s(CLOCK_MONOTONIC);
    if (lease_write(q->claim, &q->lease, &e) < 0) {
        char buf[2048];
        err_format(&e, buf, sizeof buf);
        queue_log(name, "worker: --queue %s: %s; returned it to the queue", q->dir, buf);
        (void)fileio_rename_noreplace(q->claim, from);
        return -1;
    }
    queue_log(name, "claimed by pid %ld on %s", q->lease.pid, q->lease.host);
    return 0;
}

void queue_claim_source(const struct queue *q, const char *claim, char *out, size_t n)
{
    char target[2048];
    ssize_t len = readlink(claim, target, sizeof target - 1);
    if (len <= 0 || target[0] == '/') {
        snprintf(out, n, "%s", claim);
        return;
    }
    target[len] = 0;
    snprintf(out, n, "%s/%s", q->dir, target);
}

int queue_claim_still_ours(struct queue *q)
{
    struct lease l;
    struct stat st;
    double age;
    return lstat(q->claim, &st) == 0 && lease_read(q->claim, &l, &age) == 0 &&
           strcmp(l.token, q->lease.token) == 0;
}

/* run_opts.still_held: queue_claim_still_ours, asked just before each output is renamed. */
static int still_held(void *arg)
{
    return queue_claim_still_ours(arg);
}

/* run_opts.may_write: a render whose claim was taken over meanwhile (our lease judged dead while
   we were stopped or hung) writes nothing, lest it replace the new holder's outputs; nor does one
   whose output folder `dir` holds the outputs of another job file of the queue with the same
   `name:` (q->name_owner says which). */
static int may_write(void *arg, const char *dir)
{
    struct queue *q = arg;
    if (!queue_claim_still_ours(q))
        return 0;
    if (!queue_claim_name_owner(q, dir, q->name_owner, sizeof q->name_owner))
        return 1;
    snprintf(q->name_dir, sizeof q->name_dir, "%s", dir);
    return 0;
}

struct run_opts queue_claim_run_opts(const struct queue *q, struct queue *held)
{
    struct run_opts ro = q->o->run;
    ro.out_dir = q->done;
    ro.stop = q->stop;
    ro.tick = tick;
    ro.may_write = may_write;
    ro.still_held = still_held;
    ro.lock_wait_s = q->o->lease_timeout_s;
    ro.tick_arg = held;
    return ro;
}

int queue_claim_name_owner(const struct queue *q, const char *dir, char *owner, size_t n)
{
    /* A sidecar's job_file is compared as it reads back: a file named in Latin-1 ("caf\xe9.yaml")
       is recorded as "caf\ufffd.yaml", and must still be the same file as itself when re-queued. */
    const char *base_name = q->as_name[0]            ? q->as_name
                            : strrchr(q->claim, '/') ? strrchr(q->claim, '/') + 1
                                                     : q->claim;
    char mine[2048];
    if (json_string_read_back(base_name, mine, sizeof mine) < 0)
        return 0;
    const char *folder = strrchr(dir, '/') ? strrchr(dir, '/') + 1 : dir;
    if (folder[0] == '.') /* no job's name: DIR/done/.cache/, the references all compare jobs share */
        return 0;
    DIR *d = opendir(dir);
    int taken = 0;
    if (!d)
        return 0;
    struct dirent *de;
    while (!taken && (de = readdir(d))) {
        size_t len = strlen(de->d_name);
        char path[4096];
        struct sidecar_info info;
        struct err e;
        if (de->d_name[0] == '.' || len < 6 || strcmp(de->d_name + len - 5, ".json"))
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        if (sidecar_read(path, &info, &e) < 0 || !info.job_file[0])
            continue;
        const char *base = strrchr(info.job_file, '/') ? strrchr(info.job_file, '/') + 1 : info.job_file;
        if (strcmp(base, mine) != 0) {
            snprintf(owner, n, "%s", info.job_file);
            taken = 1;
        }
    }
    closedir(d);
    return taken;
}

int queue_claim_lock(struct queue *q)
{
    for (int i = 0; i < 100; i++) {
        if (lease_lock(q->claim, q->o->lease_timeout_s) == 0)
            return 0;
        struct timespec nap = {0, 10 * 1000 * 1000};
        nanosleep(&nap, NULL);
    }
    return -1;
}

void queue_claim_file(struct queue *q, const char *name, const char *to_dir)
{
    char to[2048];
    snprintf(to, sizeof to, "%s/%s", to_dir, name);
    /* The lease goes first, under the claim's recovery lock: removed after the move, it could be
       the lease of another worker that claimed a re-queued file of this name in between (issue 21,
       defect 7). The lock keeps recoverers away while the claim has no lease; without it (held
       for a second by another), only the check that the lease is still ours stands guard. */
    int locked = queue_claim_lock(q) == 0;
    if (!queue_claim_still_ours(q)) {
        queue_log(name, "the claim was taken over before it was filed; leaving the job to it\n");
        if (locked)
            lease_unlock(q->claim);
        return;
    }
    lease_remove(q->claim);
    if (rename(q->claim, to) < 0) {
        int saved = errno;
        struct err e;
        (void)lease_write(q->claim, &q->lease, &e); /* still ours, in running/: the next scan decides */
        queue_log(name, "cannot move it to %s: %s\n", to, strerror(saved));
    }
    if (locked)
        lease_unlock(q->claim);
}
