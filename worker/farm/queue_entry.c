/* queue_entry: one claimed entry of a study spread over a queue, processed: a reference or an
   image rendered, or the gather; then filed (done/, failed/, or back to the study's queue). */
#include "queue_entry.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "job/outdir.h"
#include "lease.h"
#include "queue_file.h"
#include "queue_log.h"
#include "queue_part.h"
#include "study/run/jobfile_run.h"
#include "study/run/study_fan.h"

/* The entry claimed in hand back among the study's waiting entries, under its recovery lock. */
static void give_back_quietly(struct queue *sq, const char *ticket)
{
    if (queue_claim_lock(sq) < 0)
        return; /* a recoverer holds it: the claim is its */
    if (queue_claim_still_ours(sq))
        (void)queue_claim_return(sq, sq->claim, ticket);
    lease_unlock(sq->claim);
}

/* Render entry `ticket` (kind, indices and part in its name) of the study loaded as f. */
static int render(struct queue *q, struct queue *sq, struct study_fan *f, const char *ticket, char *msg,
                  size_t n)
{
    int attempts = 0, rc;
    struct spread_entry x;
    struct err e = {0};
    struct run_opts ro = queue_claim_run_opts(q, sq);
    if (spread_plan_parse(ticket, &x) < 0) {
        snprintf(msg, n, "%s: not a render entry", ticket);
        return 2;
    }
    do {
        sq->attempt = ++attempts;
        rc = queue_part_render(f, &x, &ro, msg, n, &e);
    } while (rc == 1 && !*q->stop && attempts <= q->o->retries);
    if (rc != 0)
        err_format(&e, msg, n);
    if (rc != 0 && outdir_env_error(&e))
        sq->env_err = e;
    return rc;
}

/* The recovery locks and leases that workers killed at the wrong moment left in the study's running/
   (their claims filed meanwhile), removed once the study is gathered: nothing can claim there any more
   but the gather itself (keep). */
static void sweep_running(const char *sd, const char *keep)
{
    char dir[2200], path[2600], claim[2600];
    struct stat st;
    snprintf(dir, sizeof dir, "%s/running", sd);
    DIR *d = opendir(dir);
    struct dirent *de;
    while (d && (de = readdir(d))) {
        size_t len = strlen(de->d_name);
        size_t cut = len > 5 && !strcmp(de->d_name + len - 5, ".lock")    ? 5
                     : len > 6 && !strcmp(de->d_name + len - 6, ".lease") ? 6
                                                                          : 0;
        if (!cut || !strncmp(de->d_name, keep, strlen(keep)))
            continue;
        snprintf(claim, sizeof claim, "%s/%.*s", dir, (int)(len - cut), de->d_name);
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        if (lstat(claim, &st) < 0)
            unlink(path);
    }
    if (d)
        closedir(d);
}

/* The study an entry belongs to: its folder sd (DIR/spread/<stem>), its job file `from` (read as if
   at `as`, where it was queued) and its record k (study.key). */
struct entry_study {
    const char *sd, *stem, *from, *as;
    const struct study_key *k;
};

/* The gather: the whole job (the study's job file, read once) run with every render current, which
   writes its summary, chart, report and verdict; then its job file goes from the study's job/ to
   DIR/done/. */
static int gather(struct queue *q, struct queue *sq, const struct entry_study *s, char *msg, size_t n,
                  char *damaged, size_t nd)
{
    const char *from = s->from, *as = s->as, *sd = s->sd, *stem = s->stem;
    const struct study_key *k = s->k;
    char job[2300], to[2300];
    struct jobfile jf;
    struct jobfile_outcome out = {0};
    struct err e = {0};
    snprintf(job, sizeof job, "%s/job/%s.yaml", sd, stem);
    snprintf(to, sizeof to, "%s/%s.yaml", q->done, stem);
    struct stat st;
    if (lstat(job, &st) < 0) { /* gathered by a worker killed before it filed this entry? */
        int linked = lstat(to, &st) == 0 && S_ISLNK(st.st_mode);
        if (linked || queue_study_key_same(to, k->job_hash)) {
            snprintf(msg, n, "already gathered (%s.yaml is in %s/)", stem, q->done);
            return 0;
        }
        snprintf(msg, n, "%s: the study's job file is gone from its job/ folder and was never gathered", job);
        return 2;
    }
    struct run_opts ro = queue_claim_run_opts(q, sq);
    ro.force = 0; /* every render is current: --force would render them all again here */
    int rc = 2;
    if (jobfile_open(&jf, from, as, &e) == 0 && jf.hash != k->job_hash) {
        snprintf(damaged, nd, "%s: not the job that was spread (its hash is not the one study.key records)",
                 from);
    } else if (lstat(job, &st) == 0 && !S_ISLNK(st.st_mode) && !queue_study_key_same(job, k->job_hash)) {
        snprintf(damaged, nd,
                 "%s: changed since the study was spread (its hash is not the one study.key records)", job);
    } else if (e.msg[0] || jf.kind == JOBFILE_PLAIN) { /* not the compare job it was */
        if (!e.msg[0])
            err_set(&e, as, 0, 0, "not a compare job");
        err_format(&e, out.line, sizeof out.line);
    } else {
        rc = jobfile_run(&jf, &ro, NULL, NULL, &out); /* prints its summary line */
    }
    jobfile_close(&jf);
    snprintf(msg, n, "%s", out.line);
    if (damaged[0])
        return 2;
    if (rc != 0 && outdir_env_error(&out.e))
        sq->env_err = out.e;
    if (rc != 0 || !queue_claim_still_ours(sq))
        return rc;
    if (lstat(job, &st) == 0 && !S_ISLNK(st.st_mode) && !queue_study_key_same(job, k->job_hash)) {
        snprintf(damaged, nd,
                 "%s: changed since the study was spread (its hash is not the one study.key records)",
                 job); /* while it was gathered */
        return 2;
    }
    if (rename(job, to) < 0) {
        snprintf(msg, n, "cannot move %s to %s: %s", job, to, strerror(errno));
        return 1;
    }
    sweep_running(sd, QUEUE_STUDY_GATHER);
    snprintf(msg, n,
             "gathered into %s/%s/ (summary.csv, chart.svg, report.html, verdict.json); %s.yaml moved to %s/",
             q->done, out.name, stem, q->done);
    return 0;
}

void queue_entry_process(struct queue *q, struct queue *sq, const char *sd, const char *stem,
                         const struct study_key *k, const char *ticket, char *damaged, size_t n_damaged)
{
    char label[2600], from[2200], as[2200], msg[4096], log_name[300];
    struct study_fan f = {0};
    struct jobfile jf = {0};
    struct err e = {0};
    int rc;
    damaged[0] = 0;
    snprintf(label, sizeof label, "%s/%s/%s", QUEUE_STUDY_DIR, stem, ticket);
    snprintf(from, sizeof from, "%s/study.job", sd);
    snprintf(as, sizeof as, "%s/%s.yaml", q->dir, stem);
    outdir_stem(ticket, log_name, sizeof log_name);
    queue_claim_begin(sq);
    if (!queue_study_key_has(k, ticket)) { /* a claim recovered in running/ that the study never wrote */
        snprintf(msg, sizeof msg, "not an entry of the study (study.key names its entries)");
        rc = 2;
    } else if (!strcmp(ticket, QUEUE_STUDY_GATHER)) {
        struct entry_study s = {.sd = sd, .stem = stem, .from = from, .as = as, .k = k};
        rc = gather(q, sq, &s, msg, sizeof msg, damaged, n_damaged);
    } else if (jobfile_open(&jf, from, as, &e) == 0 && jf.hash != k->job_hash) { /* read once, checked */
        snprintf(damaged, n_damaged,
                 "%s: not the job that was spread (its hash is not the one study.key records)", from);
        rc = 2;
    } else if (e.msg[0] || study_fan_load(&jf, &f, &e) < 0) {
        err_format(&e, msg, sizeof msg);
        rc = 2;
    } else {
        rc = render(q, sq, &f, ticket, msg, sizeof msg);
    }
    study_fan_free(&f);
    jobfile_close(&jf);
    if ((sq->lost || !queue_claim_still_ours(sq)) && !queue_scan_has(sd, "study.job"))
        queue_log(label,
                  "the study's folder %s/ was removed while it rendered (cancelled): render stopped, "
                  "nothing written\n",
                  sd);
    else if (sq->lost || !queue_claim_still_ours(sq))
        queue_file_say_lost(sq, label);
    else if (damaged[0]) /* back, unsaid: the caller ends the study with one line */
        give_back_quietly(sq, ticket);
    else if (rc == 1 && *q->stop)
        queue_file_stopped(sq, ticket);
    else if (rc != 0 && sq->env_err.msg[0]) { /* this machine's fault: back to the study's queue */
        queue_file_env_stop(sq, ticket, &sq->env_err);
        q->env_failed = 1;
        queue_file_note_rc(q, 2);
    } else if (rc == 0) {
        queue_log(label, "%s\n", msg);
        queue_claim_file(sq, ticket, sq->done);
    } else {
        queue_log(label, "%s; moved to %s/\n", msg, sq->failed);
        queue_file_log(sq, ticket, log_name, msg, 0, sq->attempt);
        queue_file_failed(sq, ticket, "");
        queue_file_note_rc(q, rc);
    }
    queue_claim_end(sq);
}
