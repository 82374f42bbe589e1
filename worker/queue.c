/* queue: claim by rename(), lease while rendering, file as done or failed, recover dead claims. */
#include "queue.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "compare.h"
#include "fileio.h"
#include "lease.h"
#include "queue_scan.h"

/* The only global state: set by SIGINT/SIGTERM, read by the queue loop and the farm. */
static volatile sig_atomic_t queue_stop;

static void on_signal(int sig)
{
    if (queue_stop) { /* the second signal: die now, as the user asked */
        signal(sig, SIG_DFL);
        raise(sig);
        return;
    }
    queue_stop = sig;
}

void queue_signals_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL); /* no SA_RESTART: a poll's sleep ends at once */
    sigaction(SIGTERM, &sa, NULL);
}

struct queue {
    const struct queue_opts *o;
    char dir[1024], running[1100], done[1100], failed[1100];
    struct lease lease; /* ours, for the claim in hand */
    char claim[2048];   /* DIR/running/X.yaml while a job is held */
    struct timespec last_touch;
    int worst;
    struct queue_scan scan; /* the waiting jobs seen by the last scan */
};

static double since(const struct timespec *t)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (now.tv_sec - t->tv_sec) + (now.tv_nsec - t->tv_nsec) * 1e-9;
}

/* The farm's progress callback (every 5 ms): renew the lease about once a second, or four times
   per --lease-timeout when that is shorter (renewed only once a second, a live claim looked dead
   to others for part of every second under a timeout of less than one, and was rendered again). */
static void tick(void *arg)
{
    struct queue *q = arg;
    double every = q->o->lease_timeout_s / 4 < 1.0 ? q->o->lease_timeout_s / 4 : 1.0;
    if (since(&q->last_touch) < every)
        return;
    lease_touch(q->claim);
    clock_gettime(CLOCK_MONOTONIC, &q->last_touch);
}

/* Move the claim at `claim` (file `name`) back to DIR under its recovery lock; the lease goes first
   so that nobody can mistake a fresh claim's lease for the old one. 0 when moved. */
static int return_claim(struct queue *q, const char *claim, const char *name)
{
    char back[2048];
    snprintf(back, sizeof back, "%s/%s", q->dir, name);
    lease_remove(claim);
    return rename(claim, back);
}

/* A job of the claim's file name waits in DIR again (re-submitted while the claim ran): the claim
   cannot go back without replacing it, nor can it wait there, since that name stays claimed. */
static int name_waiting(struct queue *q, const char *name)
{
    char back[2048];
    struct stat st;
    snprintf(back, sizeof back, "%s/%s", q->dir, name);
    return lstat(back, &st) == 0;
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
    clock_gettime(CLOCK_MONOTONIC, &q->last_touch);
    if (lease_write(q->claim, &q->lease, &e) == 0)
        return 0;
    char buf[2048];
    err_format(&e, buf, sizeof buf);
    err_print("queue: %s: %s\n", name, buf);
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
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    if (lstat(path, &st) == 0 && S_ISREG(st.st_mode) &&
        (now.tv_sec - st.st_mtim.tv_sec) + (now.tv_nsec - st.st_mtim.tv_nsec) * 1e-9 > q->o->lease_timeout_s)
        unlink(path);
}

/* Return every dead worker's claim to the queue. A dead claim whose file name waits in DIR again
   is taken over in place instead (its name into `adopted`, and 1: process it now), so that both
   jobs are rendered, this one first. */
static int recover_stale(struct queue *q, char *adopted, size_t n)
{
    DIR *d = opendir(q->running);
    int took = 0;
    if (!d)
        return 0;
    struct dirent *de;
    while (!took && (de = readdir(d))) {
        char claim[2048], why[512];
        remove_dead_lease_temp(q, de->d_name);
        if (!queue_is_job_file(de->d_name))
            continue;
        snprintf(claim, sizeof claim, "%s/%s", q->running, de->d_name);
        if (!lease_stale(claim, q->o->lease_timeout_s, why, sizeof why))
            continue;
        if (lease_lock(claim, q->o->lease_timeout_s) < 0)
            continue;
        /* judged again under the lock: another recoverer may have moved it meanwhile */
        if (lease_stale(claim, q->o->lease_timeout_s, why, sizeof why)) {
            if (!name_waiting(q, de->d_name)) {
                if (return_claim(q, claim, de->d_name) == 0)
                    err_print("queue: %s: returned to the queue: %s\n", de->d_name, why);
            } else if (adopt_claim(q, claim, de->d_name) == 0) {
                err_print("queue: %s: taken over in %s/ (a newer %s waits in the queue): %s\n", de->d_name,
                          q->running, de->d_name, why);
                snprintf(adopted, n, "%s", de->d_name);
                took = 1;
            }
        }
        lease_unlock(claim);
    }
    closedir(d);
    return took;
}

/* Claim DIR/name into running/ and write our lease. 0 when the job is ours; 1 when another worker
   was first, or a job of its file name is running; -1 when the queue cannot be written (said on
   stderr: a read-only DIR, no permission, a full disk). */
static int claim(struct queue *q, const char *name)
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
        err_print("worker: --queue %s: cannot claim %s into %s/: %s", q->dir, name, q->running,
                  strerror(errno));
        return -1;
    }
    lease_init(&q->lease);
    clock_gettime(CLOCK_MONOTONIC, &q->last_touch);
    if (lease_write(q->claim, &q->lease, &e) < 0) {
        char buf[2048];
        err_format(&e, buf, sizeof buf);
        err_print("worker: --queue %s: %s: %s; returned it to the queue", q->dir, name, buf);
        rename(q->claim, from);
        return -1;
    }
    return 0;
}

/* Still ours? Nobody took the claim away while we rendered (a lease judged dead elsewhere). */
static int still_ours(struct queue *q)
{
    struct lease l;
    double age;
    return lease_read(q->claim, &l, &age) == 0 && strcmp(l.token, q->lease.token) == 0;
}

/* run_opts.may_write: a render whose claim was taken over meanwhile (our lease judged dead while
   we were stopped or hung) writes nothing, lest it replace the new holder's outputs. */
static int claim_held(void *arg)
{
    return still_ours(arg);
}

/* Move the claim to done/ or failed/ and drop the lease. */
static void file_claim(struct queue *q, const char *name, const char *to_dir)
{
    char to[2048];
    snprintf(to, sizeof to, "%s/%s", to_dir, name);
    if (rename(q->claim, to) < 0)
        err_print("queue: %s: cannot move it to %s: %s\n", name, to, strerror(errno));
    lease_remove(q->claim);
}

/* failed/<name>.log: what went wrong, the signal, the attempts. */
static void write_log(struct queue *q, const char *name, const char *job_name, const char *error, int sig,
                      int attempts)
{
    char path[2048], text[8192];
    int n = snprintf(text, sizeof text, "job: %s/%s\nerror: %s\n", q->dir, name, error);
    if (sig)
        n += snprintf(text + n, sizeof text - n, "signal: %d (%s)\n", sig, strsignal(sig));
    time_t t = time(NULL);
    char when[64];
    strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", gmtime(&t));
    n += snprintf(text + n, sizeof text - n, "attempts: %d\nworker: pid %ld on %s\ntime: %s\n", attempts,
                  q->lease.pid, q->lease.host, when);
    snprintf(path, sizeof path, "%s/%s.log", q->failed, job_name);
    struct err e;
    if (fileio_write_atomic(path, text, (size_t)(n < (int)sizeof text ? n : (int)sizeof text - 1), &e) < 0)
        err_print("queue: %s: %s\n", name, e.msg);
}

/* Hand the claim in hand back to the queue (a stop signal): under its recovery lock, and only
   while it is still ours. */
static void give_back(struct queue *q, const char *name)
{
    int locked = 0;
    for (int i = 0; i < 100 && !(locked = lease_lock(q->claim, q->o->lease_timeout_s) == 0); i++) {
        struct timespec nap = {0, 10 * 1000 * 1000};
        nanosleep(&nap, NULL);
    }
    if (!locked) { /* another worker is recovering it (our lease looked dead): the claim is its now */
        err_print("%s: stopped by signal %d; its recovery lock is held, so it stays in %s/ for recovery",
                  name, (int)queue_stop, q->running);
        return;
    }
    if (!still_ours(q))
        ;
    else if (name_waiting(q, name))
        err_print("%s: stopped by signal %d; a newer %s waits in the queue, so this one stays in %s/ for the "
                  "next worker\n",
                  name, (int)queue_stop, name, q->running);
    else if (return_claim(q, q->claim, name) == 0)
        err_print("%s: stopped by signal %d, returned to the queue\n", name, (int)queue_stop);
    lease_unlock(q->claim);
}

static void note_rc(struct queue *q, int rc)
{
    if (rc > q->worst)
        q->worst = rc;
}

/* A compare job: its combinations render into done/<name>/ as one job; a retry after a crash
   renders only the combinations still missing (they resume by hash). Invalid: failed/. */
static void process_compare(struct queue *q, const char *name, const char *from, const char *as,
                            const char *stem)
{
    struct run_opts ro = q->o->run;
    ro.out_dir = q->done;
    ro.stop = &queue_stop;
    ro.tick = tick;
    ro.tick_arg = q;
    char last[2048] = "";
    int attempts = 0, rc;
    do {
        attempts++;
        rc = compare_main_as(from, as, &ro, last, sizeof last);
    } while (rc == 1 && !queue_stop && attempts <= q->o->retries);
    if (rc == 1 && queue_stop) {
        give_back(q, name);
        return;
    }
    if (!still_ours(q))
        return;
    if (rc == 0) {
        file_claim(q, name, q->done);
        return;
    }
    err_print("%s: %s compare job, moved to %s/\n", name, rc == 2 ? "invalid" : "failed", q->failed);
    write_log(q, name, stem, last, 0, attempts);
    file_claim(q, name, q->failed);
    note_rc(q, rc);
}

/* The file to read the claimed job from: the claim itself, or, when the job was a symbolic link
   with a relative target, that target seen from DIR, where the link was made (the claim moved
   the link into running/, where its target would be looked up beside running/). */
static void claim_source(const struct queue *q, char *out, size_t n)
{
    char target[2048];
    ssize_t len = readlink(q->claim, target, sizeof target - 1);
    if (len <= 0 || target[0] == '/') {
        snprintf(out, n, "%s", q->claim);
        return;
    }
    target[len] = 0;
    snprintf(out, n, "%s/%s", q->dir, target);
}

/* Load, render (retrying crashed renders) and file the claimed job DIR/running/name. */
static void process(struct queue *q, const char *name)
{
    char as[2048], from[4096], msg[2048], stem[256];
    struct job j;
    struct err e;
    struct run_result rr;
    snprintf(as, sizeof as, "%s/%s", q->dir, name);
    snprintf(stem, sizeof stem, "%.*s", (int)strlen(name) - 5, name);
    claim_source(q, from, sizeof from);
    if (compare_is_compare_job(from)) {
        process_compare(q, name, from, as, stem);
        return;
    }
    if (job_load_as(from, as, &j, &e) < 0) { /* invalid: never retried */
        err_format(&e, msg, sizeof msg);
        err_print("%s", msg);
        err_print("%s: invalid job, moved to %s/", name, q->failed);
        write_log(q, name, stem, msg, 0, 0);
        file_claim(q, name, q->failed);
        note_rc(q, 2);
        return;
    }
    struct run_opts ro = q->o->run;
    ro.out_dir = q->done;
    ro.stop = &queue_stop;
    ro.tick = tick;
    ro.may_write = claim_held;
    ro.tick_arg = q;
    int attempts = 0, rc;
    for (;;) {
        attempts++;
        rc = run_job(&j, &ro, &rr, &e);
        if (rc != 1 || !rr.farm.child_crashed || attempts > q->o->retries || queue_stop)
            break;
        err_format(&e, msg, sizeof msg);
        err_print("%s: %s; retrying (attempt %d of %d)\n", name, msg, attempts + 1, q->o->retries + 1);
    }
    if (rc == 1 && (rr.farm.stopped || queue_stop)) {
        give_back(q, name);
        return;
    }
    if (!still_ours(q)) {
        err_print("%s: the claim was taken over (our lease was judged dead); leaving the job to it\n", name);
        return;
    }
    if (rc == 0) {
        if (rr.skipped)
            err_print("%s: up to date in %s/%s/ (same job hash), skipped; --force renders it again\n", name,
                      q->done, j.name);
        else
            run_print_summary(&j, &rr);
        file_claim(q, name, q->done);
        return;
    }
    err_format(&e, msg, sizeof msg);
    err_print("%s: %s; moved to %s/ after %d attempt%s\n", name, msg, q->failed, attempts,
              attempts > 1 ? "s" : "");
    write_log(q, name, j.name, msg, rr.farm.child_signal, attempts);
    file_claim(q, name, q->failed);
    note_rc(q, rc);
}

/* Sleep up to s seconds; a signal ends it early. */
static void nap(double s)
{
    struct timespec ts = {(time_t)s, (long)((s - (time_t)s) * 1e9)};
    nanosleep(&ts, NULL);
}

int queue_main(const struct queue_opts *qo)
{
    struct queue q;
    struct stat st;
    struct err e;
    memset(&q, 0, sizeof q);
    q.o = qo;
    snprintf(q.dir, sizeof q.dir, "%s", qo->dir);
    for (size_t n = strlen(q.dir); n > 1 && q.dir[n - 1] == '/'; n--)
        q.dir[n - 1] = 0;
    int bad = stat(q.dir, &st) < 0 ? errno : S_ISDIR(st.st_mode) ? 0 : ENOTDIR;
    if (bad) {
        err_print("worker: --queue %s: %s\n", q.dir, strerror(bad));
        return 2;
    }
    snprintf(q.running, sizeof q.running, "%s/running", q.dir);
    snprintf(q.done, sizeof q.done, "%s/done", q.dir);
    snprintf(q.failed, sizeof q.failed, "%s/failed", q.dir);
    if (run_mkdirs(q.running, &e) < 0 || run_mkdirs(q.done, &e) < 0 || run_mkdirs(q.failed, &e) < 0) {
        err_print("worker: --queue %s: %s\n", q.dir, e.msg);
        return 2;
    }
    while (!queue_stop) {
        char adopted[256];
        if (recover_stale(&q, adopted, sizeof adopted)) {
            process(&q, adopted);
            continue;
        }
        struct queue_waiting *w;
        int n = queue_scan_waiting(&q.scan, q.dir, &w), took = 0;
        if (n < 0) {
            err_print("worker: --queue %s: %s\n", q.dir, strerror(errno));
            q.worst = 2;
            break;
        }
        int unusable = 0;
        for (int i = 0; i < n && !took && !unusable && !queue_stop; i++) {
            int got = claim(&q, w[i].name);
            unusable = got < 0;
            if (got == 0) {
                process(&q, w[i].name);
                took = 1;
            }
        }
        free(w);
        if (unusable) {
            q.worst = 2;
            break;
        }
        if (took)
            continue;
        if (qo->once)
            break;
        nap(qo->poll_s);
    }
    queue_scan_free(&q.scan);
    return q.worst;
}
