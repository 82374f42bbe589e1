/* queue: claim by rename(), lease while rendering, file as done or failed, recover dead claims. */
#include "queue.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "study/run/jobfile_run.h"
#include "base/fileio.h"
#include "lease.h"
#include "queue_claim.h"
#include "queue_file.h"
#include "queue_inputs.h"
#include "queue_log.h"
#include "queue_scan.h"
#include "queue_status.h"
#include "queue_drain.h"
#include "queue_study.h"
#include "job/outdir.h"
#include "job/run.h"

/* The only global state: set by SIGINT/SIGTERM, read by the queue loop and the render in hand. */
static volatile sig_atomic_t queue_stop;

static void on_signal(int sig)
{
    if (queue_stop > 0) { /* the second signal: die now, as the user asked */
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

/* The claim's output folder holds the outputs of another job file of the queue with the same name
   (q->name_owner): filed in failed/ as invalid, the log naming that file; the folder is left as it
   is. The same file re-queued (edited or not) renders again: only another file name conflicts. */
static void name_taken(struct queue *q, const char *name, const char *log_name, const int pos[2])
{
    char msg[4600], at[32] = "";
    const char *job_name = strrchr(q->name_dir, '/') ? strrchr(q->name_dir, '/') + 1 : q->name_dir;
    if (pos && pos[0])
        snprintf(at, sizeof at, ":%d:%d", pos[0], pos[1]);
    snprintf(msg, sizeof msg,
             "%s/%s%s: name: \"%s\" is taken: %s/ holds the outputs of %s; give this job another name (or "
             "remove that folder to replace them)",
             q->dir, name, at, job_name, q->name_dir, q->name_owner);
    queue_file_invalid(q, name, log_name, msg, "name taken", 0);
}

/* The summary line of a rendered job, and its warnings, as queue log lines. */
static void log_summary(const char *name, const struct job *j, const struct run_result *rr)
{
    char line[4400];
    run_format_summary(j, rr, line, sizeof line);
    queue_log(name, "%s", line);
    if (run_format_warning(j, rr, line, sizeof line))
        queue_log(name, "%s", line);
}

/* Render (retrying crashed renders) and file the claimed plain job DIR/running/name, read into f
   (invalid when open_rc < 0, e saying why). */
static void process_job(struct queue *q, const char *name, const struct jobfile *f, int open_rc, struct err e)
{
    char msg[2048], stem[256];
    const struct job j = f->job;
    struct jobfile_outcome out;
    struct run_result *rr = &out.rr;
    outdir_stem(name, stem, sizeof stem);
    if (open_rc < 0 || queue_inputs_check(q->dir, &j, &e) < 0) { /* invalid: never retried */
        err_format(&e, msg, sizeof msg);
        queue_file_invalid(q, name, stem, msg, "invalid job", 1);
        return;
    }
    snprintf(q->name_dir, sizeof q->name_dir, "%s/%s", q->done, j.name);
    if (queue_claim_name_owner(q, q->name_dir, q->name_owner, sizeof q->name_owner)) {
        name_taken(q, name, stem, job_at(&j, "name"));
        return;
    }
    struct run_opts ro = queue_claim_run_opts(q, q); /* q->stop is &queue_stop */
    q->processes = ro.processes > 0 ? ro.processes : j.processes;
    queue_log_check_cores(q->running, &q->lease, q->claim, name, q->processes);
    int attempts = 0, rc;
    for (;;) {
        q->attempt = ++attempts;
        rc = jobfile_run(f, &ro, NULL, NULL, &out);
        e = out.e;
        if (rc != 1 || !rr->procs.child_crashed || attempts > q->o->retries || queue_stop)
            break;
        err_format(&e, msg, sizeof msg);
        queue_log(name, "%s; retrying (attempt %d of %d)\n", msg, attempts + 1, q->o->retries + 1);
    }
    if (q->lost || !queue_claim_still_ours(q)) {
        queue_file_say_lost(q, name);
        return;
    }
    if (rc == 1 && (rr->procs.stopped || queue_stop)) {
        queue_file_stopped(q, name);
        return;
    }
    if (rc != 0 && outdir_env_error(&e)) { /* this machine's fault, not the job's: never failed/ */
        queue_file_env_stop(q, name, &e);
        return;
    }
    if (rc == 0) {
        if (rr->skipped)
            queue_log(name, "up to date in %s/%s/ (same job hash), skipped; --force renders it again\n",
                      q->done, j.name);
        else
            log_summary(name, &j, rr);
        queue_claim_file(q, name, q->done);
        return;
    }
    if (q->name_owner[0]) { /* another file of this name wrote its outputs while we rendered */
        name_taken(q, name, stem, job_at(&j, "name"));
        return;
    }
    err_format(&e, msg, sizeof msg);
    queue_log(name, "%s; moved to %s/ after %d attempt%s\n", msg, q->failed, attempts,
              attempts > 1 ? "s" : "");
    queue_file_log(q, name, j.name, msg, rr->procs.child_signal, attempts);
    queue_file_failed(q, name, j.name);
    queue_file_note_rc(q, rc);
}

/* The claim in hand, DIR/running/name, read once, then rendered and filed, its lease renewed
   throughout. */
static void process(struct queue *q, const char *name)
{
    char as[2048], from[4096], stem[256];
    struct jobfile f;
    struct err e = {0};
    queue_claim_begin(q);
    snprintf(as, sizeof as, "%s/%s", q->dir, name);
    outdir_stem(name, stem, sizeof stem);
    queue_claim_source(q, q->claim, from, sizeof from);
    int rc = jobfile_open(&f, from, as, &e);
    if (rc == 0 && f.kind != JOBFILE_PLAIN) /* spread over the queue as its renders */
        queue_study_expand(q, name, &f, stem);
    else
        process_job(q, name, &f, rc, e);
    jobfile_close(&f);
    queue_claim_end(q);
}

/* DIR/name can never run (queue_scan's unrunnable): moved to failed/ with a log saying why, by
   whichever worker's rename() gets it; when it cannot be moved, said once per worker. */
static void file_unrunnable(struct queue *q, const char *name)
{
    char from[2048], msg[2600];
    snprintf(from, sizeof from, "%s/%s", q->dir, name);
    snprintf(msg, sizeof msg, "%s: cannot run: %s (a job file is a regular file, or a link to one)", from,
             fileio_kind(from) ? fileio_kind(from) : "gone");
    if (queue_file_aside(q, name, name, msg) == 0) {
        q->filed++;
        return;
    }
    if (errno == ENOENT) /* another worker filed it */
        return;
    for (int i = 0; i < q->nreported; i++)
        if (!strcmp(q->reported[i], name))
            return;
    if (q->nreported < (int)(sizeof q->reported / sizeof q->reported[0]))
        snprintf(q->reported[q->nreported++], sizeof q->reported[0], "%s", name);
    queue_log(name, "%s; cannot move it to %s/: %s\n", msg, q->failed, strerror(errno));
    queue_file_note_rc(q, 2);
}

/* Sleep up to s seconds; a signal ends it early. */
static void nap(double s)
{
    struct timespec ts = {(time_t)s, (long)((s - (time_t)s) * 1e9)};
    nanosleep(&ts, NULL);
}

/* The lease of running/name into holder, read again for up to a second while it is not yet written
   (a claimer renames the job into running/ first, then writes its lease). 0 read; -1 still not
   written; 1 the claim has left running/ meanwhile (spread, or filed). */
static int read_holder(const struct queue *q, const char *name, struct lease *holder)
{
    char claim[2048];
    double age;
    struct stat st;
    snprintf(claim, sizeof claim, "%s/%s", q->running, name);
    for (int i = 0; holder->pid == 0 && i < 20 && !queue_stop; i++) {
        nap(0.05);
        if (lstat(claim, &st) < 0)
            return 1;
        if (lease_read(claim, holder, &age) < 0)
            memset(holder, 0, sizeof *holder);
    }
    return holder->pid ? 0 : -1;
}

/* 1 when a compare job claimed by another worker is being spread (queue_study_spreading): a --once
   worker waits for its renders rather than leave them all to that worker. Said once per job, with
   its holder once the holder's lease is written. */
static int spreading(struct queue *q)
{
    char name[256];
    struct lease holder;
    if (!queue_study_spreading(q, &holder, name, sizeof name)) {
        q->spreading[0] = 0;
        return 0;
    }
    if (!strcmp(q->spreading, name)) /* said already */
        return 1;
    int known = read_holder(q, name, &holder);
    if (known == 1) /* spread (or filed) while we looked: the next scan sees what became of it */
        return 1;
    if (known == 0)
        queue_log(name,
                  "a compare job claimed by pid %ld on %s: waiting for it to be spread, to take its "
                  "renders\n",
                  holder.pid, holder.host[0] ? holder.host : "?");
    else
        queue_log(name, "a compare job claimed (its lease not yet written): waiting for it to be spread, to "
                        "take its renders\n");
    snprintf(q->spreading, sizeof q->spreading, "%s", name);
    return 1;
}

/* When a folder of dir (not the queue's own) holds a file X.yaml, a hint that it is no job there
   (only dir/X.yaml are: a job put one folder too deep); else "". hint is the buffer. */
static const char *subfolder_hint(const char *dir, char *hint, size_t n)
{
    const char *own[] = {"running", "done", "failed", QUEUE_STUDY_DIR};
    DIR *d = opendir(dir);
    struct dirent *de;
    hint[0] = 0;
    while (d && !hint[0] && (de = readdir(d))) {
        char sub[2300];
        struct stat st;
        int skip = de->d_name[0] == '.';
        for (int i = 0; i < 4 && !skip; i++)
            skip = !strcmp(de->d_name, own[i]);
        snprintf(sub, sizeof sub, "%s/%s", dir, de->d_name);
        if (skip || lstat(sub, &st) < 0 || !S_ISDIR(st.st_mode))
            continue;
        DIR *s = opendir(sub);
        struct dirent *f;
        while (s && !hint[0] && (f = readdir(s)))
            if (queue_scan_is_job_file(f->d_name))
                snprintf(
                    hint, n,
                    "; %s/%s is in a folder of the queue, where no worker looks: a job goes in %s/ itself "
                    "(a suite's study files may stay there)",
                    sub, f->d_name, dir);
        if (s)
            closedir(s);
    }
    if (d)
        closedir(d);
    return hint;
}

/* Whether directory dir is "/" under any spelling ("/", "//", "/tmp/..", a link to it): its parent
   is itself. A queue there would make /running, /done and /failed. */
static int is_root_dir(const char *dir)
{
    char up[1100];
    struct stat st, pst;
    snprintf(up, sizeof up, "%s/..", dir);
    return stat(dir, &st) == 0 && stat(up, &pst) == 0 && pst.st_dev == st.st_dev && pst.st_ino == st.st_ino;
}

int queue_main(const struct queue_opts *qo)
{
    struct queue q;
    struct err e;
    memset(&q, 0, sizeof q);
    q.o = qo;
    q.stop = &queue_stop;
    if (queue_status_dir("worker: --queue ", qo->dir, q.dir, sizeof q.dir))
        return 2;
    if (is_root_dir(q.dir)) {
        err_print("worker: --queue %s: is the file system's root directory; give the queue a directory of "
                  "its own (running/, done/ and failed/ are made in it)\n",
                  q.dir);
        return 2;
    }
    snprintf(q.running, sizeof q.running, "%s/running", q.dir);
    snprintf(q.done, sizeof q.done, "%s/done", q.dir);
    snprintf(q.failed, sizeof q.failed, "%s/failed", q.dir);
    if (outdir_mkdirs(q.running, NULL, &e) < 0 || outdir_mkdirs(q.done, NULL, &e) < 0 ||
        outdir_mkdirs(q.failed, NULL, &e) < 0) {
        err_print("worker: --queue %s: %s\n", q.dir, e.msg);
        return 2;
    }
    while (!queue_stop && !q.env_failed) {
        char adopted[256];
        if (queue_claim_recover(&q, adopted, sizeof adopted)) {
            q.took++;
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
        for (int i = 0; i < q.scan.nunrunnable && !queue_stop; i++)
            file_unrunnable(&q, q.scan.unrunnable[i]);
        int unusable = 0;
        for (int i = 0; i < n && !took && !unusable && !queue_stop; i++) {
            int got = queue_claim_take(&q, w[i].name);
            unusable = got < 0;
            took = got == 0;
            if (took)
                process(&q, w[i].name);
        }
        free(w);
        if (unusable) {
            q.worst = 2;
            break;
        }
        q.waits_requeue[0] = 0;
        int study = took ? 1 : queue_drain_work(&q); /* 1: a job or a study's entry processed */
        q.took += study == 1;
        if (study == 1)
            continue;
        if (qo->once && study != 2 && !spreading(&q)) {
            if (q.waits_requeue[0]) /* it ends unfinished: say why and what finishes it */
                queue_log(q.waits_requeue,
                          "the study waits for its failed renders (%s/%s/%s/failed/) to be requeued: worker "
                          "requeue %s %s\n",
                          q.dir, QUEUE_STUDY_DIR, q.waits_requeue, q.dir, q.waits_requeue);
            char hint[1200] = "";
            if (!q.took && !qo->run.quiet) /* a batch task with nothing to do says so */
                err_print("worker: --queue %s: no job waiting, nothing to do%s%s\n", q.dir,
                          q.filed ? " (what could not run was moved to failed/)" : "",
                          subfolder_hint(q.dir, hint, sizeof hint));
            break;
        }
        nap(qo->poll_s);
    }
    queue_scan_free(&q.scan);
    return q.worst;
}
