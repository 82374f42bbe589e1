/* queue_file: filing a claim that ends (failed/ and its log, back to the queue, lost). */
#include "queue_file.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "base/fileio.h"
#include "job/outdir.h"
#include "lease.h"
#include "queue_log.h"

void queue_file_log(struct queue *q, const char *name, const char *job_name, const char *error, int sig,
                    int attempts)
{
    char path[2048], text[8192];
    int n = snprintf(text, sizeof text, "job: %s/%s\nerror: %s\n", q->dir, name, error);
    if (sig)
        n += snprintf(text + n, sizeof text - n, "signal: %d (%s)\n", sig, strsignal(sig));
    char when[64];
    struct lease me = q->lease;
    if (!me.pid) /* no claim in hand (an entry filed at the scan): this worker is who filed it */
        lease_init(&me);
    n += snprintf(text + n, sizeof text - n, "attempts: %d\nworker: pid %ld on %s\ntime: %s\n", attempts,
                  me.pid, me.host, queue_log_time(time(NULL), when, sizeof when));
    snprintf(path, sizeof path, "%s/%s.log", q->failed, job_name);
    struct err e;
    if (fileio_write_atomic(path, text, (size_t)(n < (int)sizeof text ? n : (int)sizeof text - 1), &e) < 0)
        queue_log(name, "%s", e.msg);
}

/* Hand the claim in hand back to the queue (why: "stopped by signal 15", or the worker's own
   failure): under its recovery lock, and only while it is still ours. One log line. */
static void give_back(struct queue *q, const char *name, const char *why)
{
    if (queue_claim_lock(q) <
        0) { /* another worker is recovering it (our lease looked dead): the claim is its now */
        queue_log(name, "%s; its recovery lock is held, so it stays in %s/ for recovery\n", why, q->running);
        return;
    }
    if (!queue_claim_still_ours(q))
        ;
    else if (queue_scan_has(q->dir, name)) /* it cannot go back without replacing it */
        queue_log(name, "%s; a newer %s waits in the queue, so this one stays in %s/ for the next worker\n",
                  why, name, q->running);
    else if (queue_claim_return(q, q->claim, name) == 0)
        queue_log(name, "%s, returned to the queue\n", why);
    else
        queue_log(name, "%s; cannot return it to the queue (%s), so it stays in %s/ for the next worker\n",
                  why, errno == EEXIST ? "a newer one of its name arrived" : strerror(errno), q->running);
    lease_unlock(q->claim);
}

void queue_file_stopped(struct queue *q, const char *name)
{
    char why[64];
    snprintf(why, sizeof why, "stopped by signal %d", (int)*q->stop);
    give_back(q, name, why);
}

void queue_file_env_stop(struct queue *q, const char *name, const struct err *e)
{
    char msg[2048], why[sizeof msg + 96];
    err_format(e, msg, sizeof msg);
    snprintf(why, sizeof why, "%s (the worker's output folder, not the job: this worker stops, exit 2)", msg);
    give_back(q, name, why);
    q->env_failed = 1;
    queue_file_note_rc(q, 2);
}

void queue_file_say_lost(struct queue *q, const char *name)
{
    struct lease l;
    struct stat st;
    double age;
    if (lstat(q->claim, &st) == 0 || errno != ENOENT || lease_read(q->claim, &l, &age) < 0 ||
        strcmp(l.token, q->lease.token)) {
        queue_log(name, "the claim was taken over (our lease was judged dead); leaving the job to it\n");
        return;
    }
    lease_remove(q->claim);
    queue_log(name, "%s was removed or moved away while it rendered: render stopped, nothing written\n",
              q->claim);
}

void queue_file_failed(struct queue *q, const char *name, const char *job_name)
{
    char dir[2048];
    if (job_name[0] && job_name[0] != '.' && !strchr(job_name, '/')) {
        outdir_dir(q->done, job_name, dir, sizeof dir);
        outdir_remove_temps(dir);
    }
    queue_claim_file(q, name, q->failed);
}

int queue_file_aside(struct queue *q, const char *name, const char *label, const char *msg)
{
    char from[2048], to[2048], stem[256];
    snprintf(from, sizeof from, "%s/%s", q->dir, name);
    snprintf(to, sizeof to, "%s/%s", q->failed, name);
    if (rename(from, to) < 0)
        return -1;
    outdir_stem(name, stem, sizeof stem);
    queue_log(label, "%s; moved to %s/\n", msg, q->failed);
    queue_file_log(q, name, stem, msg, 0, 0);
    queue_file_note_rc(q, 2);
    return 0;
}

void queue_file_invalid(struct queue *q, const char *name, const char *log_name, const char *msg,
                        const char *what, int clean)
{
    queue_log(name, "%s\n", msg);
    queue_log(name, "%s, moved to %s/\n", what, q->failed);
    queue_file_log(q, name, log_name, msg, 0, 0);
    queue_file_failed(q, name, clean ? log_name : "");
    queue_file_note_rc(q, 2);
}

void queue_file_note_rc(struct queue *q, int rc)
{
    if (rc > q->worst)
        q->worst = rc;
}
