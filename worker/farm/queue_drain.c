/* queue_drain: a queue worker's part in the studies spread over its queue: take a study's render
   entry, render it or gather, and file it. */
#include "queue_drain.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/fileio.h"
#include "job/outdir.h"
#include "lease.h"
#include "queue_file.h"
#include "queue_log.h"
#include "queue_study.h"
#include "queue_study_key.h"
#include "study/run/study_fan.h"
#include "study/run/jobfile_run.h"

/* The earliest kind ('a', 'b', 'c') of the study's entries (those its record k names) in folder dir;
   '~' when there is none. */
static char earliest_in(const char *dir, const struct study_key *k)
{
    DIR *d = opendir(dir);
    struct dirent *de;
    char first = '~';
    while (d && (de = readdir(d)))
        if (de->d_name[0] < first && queue_study_key_has(k, de->d_name))
            first = de->d_name[0];
    if (d)
        closedir(d);
    return first;
}

/* 1 when the entry may be claimed, 0 when it waits for entries of an earlier kind waiting or
   running, -1 when one of them failed (the study waits for a requeue). */
static int gate(const char *sd, const struct study_key *k, const char *ticket)
{
    char sub[2200];
    snprintf(sub, sizeof sub, "%s/failed", sd);
    char failed = earliest_in(sub, k);
    snprintf(sub, sizeof sub, "%s/running", sd);
    char running = earliest_in(sub, k), waiting = earliest_in(sd, k);
    char first = running < waiting ? running : waiting;
    if (failed < ticket[0] && failed <= first)
        return -1;
    return ticket[0] <= first ? 1 : 0;
}

/* What entry `ticket` of f rendered, for the log. */
static void describe(const struct study_fan *f, int k, enum study_fan_kind kind, int index, char *buf,
                     size_t n)
{
    const struct compare *c = study_fan_study(f, k);
    if (kind == STUDY_FAN_REFERENCE) {
        snprintf(buf, n, "%s: reference of %s in %s", c->name, c->scenes[index].name,
                 c->scenes[index].ref_path);
        return;
    }
    const struct compare_item *it = &c->items[index];
    snprintf(buf, n, "%s: image %d of %d, %s t=%g seed %llu: %.0f spp, %.2f s%s", c->name, index + 1,
             c->n_items, c->variants[it->variant], it->job.threshold, (unsigned long long)it->job.seed,
             it->spp_mean, it->wall_s, it->skipped ? " (current, not rendered again)" : "");
}

/* Render entry `ticket` (kind and indices in its name) of the study loaded as f. */
static int render(struct queue *q, struct queue *sq, struct study_fan *f, const char *ticket, char *msg,
                  size_t n)
{
    int k = -1, index = -1, attempts = 0, rc;
    enum study_fan_kind kind = ticket[0] == 'a' ? STUDY_FAN_REFERENCE : STUDY_FAN_IMAGE;
    struct err e = {0};
    if (sscanf(ticket, kind == STUDY_FAN_REFERENCE ? "a-ref-%d-%d.yaml" : "b-img-%d-%d.yaml", &k, &index) !=
        2)
        k = -1;
    struct run_opts ro = queue_claim_run_opts(q, sq);
    do {
        sq->attempt = ++attempts;
        rc = study_fan_render(f, k, kind, index, &ro, &e);
    } while (rc == 1 && !*q->stop && attempts <= q->o->retries);
    if (rc == 0)
        describe(f, k, kind, index, msg, n);
    else
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

/* The gather: the whole job (the study's job file `from`, read once as if at `as`) run with every
   render current, which writes its summary, chart, report and verdict; then its job file goes from
   the study's job/ to DIR/done/. */
static int gather(struct queue *q, struct queue *sq, const char *from, const char *as, const char *sd,
                  const char *stem, const struct study_key *k, char *msg, size_t n)
{
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
    if (jobfile_open(&jf, from, as, &e) < 0 || jf.kind == JOBFILE_PLAIN) { /* not the compare job it was */
        if (!e.msg[0])
            err_set(&e, as, 0, 0, "not a compare job");
        err_format(&e, out.line, sizeof out.line);
    } else {
        rc = jobfile_run(&jf, &ro, NULL, NULL, &out); /* prints its summary line */
    }
    jobfile_close(&jf);
    snprintf(msg, n, "%s", out.line);
    if (rc != 0 && outdir_env_error(&out.e))
        sq->env_err = out.e;
    if (rc != 0 || !queue_claim_still_ours(sq))
        return rc;
    if (lstat(job, &st) == 0 && !S_ISLNK(st.st_mode) && !queue_study_key_same(job, k->job_hash)) {
        snprintf(msg, n, "%s: changed since the study was spread (its hash is not the one study.key records)", job);
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

/* Process the claimed entry `ticket` of the study in sd (its queue sq). */
static void process_entry(struct queue *q, struct queue *sq, const char *sd, const char *stem,
                          const struct study_key *k, const char *ticket)
{
    char label[2600], from[2200], as[2200], msg[4096], log_name[300];
    struct study_fan f = {0};
    struct jobfile jf = {0};
    struct err e = {0};
    int rc;
    snprintf(label, sizeof label, "%s/%s/%s", QUEUE_STUDY_DIR, stem, ticket);
    snprintf(from, sizeof from, "%s/study.job", sd);
    snprintf(as, sizeof as, "%s/%s.yaml", q->dir, stem);
    outdir_stem(ticket, log_name, sizeof log_name);
    sq->lost = 0;
    sq->processes = 0;
    sq->name_owner[0] = 0;
    queue_claim_renew_start(sq);
    if (!queue_study_key_has(k, ticket)) { /* a claim recovered in running/ that the study never wrote */
        snprintf(msg, sizeof msg, "not an entry of the study (study.key names its entries)");
        rc = 2;
    } else if (!strcmp(ticket, QUEUE_STUDY_GATHER)) {
        rc = gather(q, sq, from, as, sd, stem, k, msg, sizeof msg);
    } else if (jobfile_open(&jf, from, as, &e) < 0 || study_fan_load(&jf, &f, &e) < 0) {
        err_format(&e, msg, sizeof msg);
        rc = 2;
    } else {
        rc = render(q, sq, &f, ticket, msg, sizeof msg);
    }
    study_fan_free(&f);
    jobfile_close(&jf);
    if ((sq->lost || !queue_claim_still_ours(sq)) && !queue_study_has(sd, "study.job"))
        queue_log(label,
                  "the study's folder %s/ was removed while it rendered (cancelled): render stopped, "
                  "nothing written\n",
                  sd);
    else if (sq->lost || !queue_claim_still_ours(sq))
        queue_file_say_lost(sq, label);
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
    queue_claim_renew_stop();
    queue_file_clear_lost_stop(sq);
}

/* 1 when folder dir holds a claim of an entry of the study (its record k). */
static int any_claim(const char *dir, const struct study_key *k)
{
    return earliest_in(dir, k) != '~';
}

/* The study's waiting entries (this scan's w, n of them; the unrunnable in sq->scan) that can never
   be claimed go to its failed/ with a log: what is not a regular file, and what the study never wrote
   (its record k). The others are left in w; their count. */
static int set_aside(struct queue *sq, const char *stem, const struct study_key *k, struct queue_waiting *w, int n)
{
    char label[600], path[2600], msg[3000];
    for (int i = 0; i < sq->scan.nunrunnable; i++) {
        const char *name = sq->scan.unrunnable[i];
        snprintf(label, sizeof label, "%s/%s/%s", QUEUE_STUDY_DIR, stem, name);
        snprintf(path, sizeof path, "%s/%s", sq->dir, name);
        snprintf(msg, sizeof msg, "%s: cannot run: %s (a study's entry is a regular file)", path,
                 fileio_kind(path) ? fileio_kind(path) : "gone");
        (void)queue_file_aside(sq, name, label, msg);
    }
    int kept = 0;
    for (int i = 0; i < n; i++) {
        if (queue_study_key_has(k, w[i].name)) {
            w[kept++] = w[i];
            continue;
        }
        snprintf(label, sizeof label, "%s/%s/%s", QUEUE_STUDY_DIR, stem, w[i].name);
        snprintf(msg, sizeof msg, "%s/%s: not an entry of the study (study.key names the entries it wrote)",
                 sq->dir, w[i].name);
        (void)queue_file_aside(sq, w[i].name, label, msg);
    }
    return kept;
}

/* One entry of the study in sd (its record k) taken and processed: 1; 2 none yet (behind renders
   running elsewhere, or a claim of it that is not yet judged dead); 0 none (q->waits_requeue names
   the study when what is left waits for its failed renders to be requeued). */
static int work_on(struct queue *q, const char *sd, const char *stem, const struct study_key *k)
{
    struct queue sq;
    memset(&sq, 0, sizeof sq);
    sq.o = q->o;
    sq.stop = q->stop;
    snprintf(sq.dir, sizeof sq.dir, "%s", sd);
    snprintf(sq.running, sizeof sq.running, "%s/running", sd);
    snprintf(sq.done, sizeof sq.done, "%s/done", sd);
    snprintf(sq.failed, sizeof sq.failed, "%s/failed", sd);
    snprintf(sq.as_name, sizeof sq.as_name, "%s.yaml", stem);
    char adopted[256];
    int result = 0, blocked = 0;
    if (queue_claim_recover(&sq, adopted, sizeof adopted)) {
        process_entry(q, &sq, sd, stem, k, adopted);
        return 1;
    }
    struct queue_waiting *w;
    int n = queue_scan_waiting(&sq.scan, sd, &w);
    if (n >= 0)
        n = set_aside(&sq, stem, k, w, n);
    queue_file_note_rc(q, sq.worst);
    for (int i = 0; i < n && result != 1 && !*q->stop; i++) {
        int g = gate(sd, k, w[i].name);
        if (g == 0)
            result = 2;
        blocked |= g < 0;
        if (g == 1 && queue_claim_take(&sq, w[i].name) == 0) {
            process_entry(q, &sq, sd, stem, k, w[i].name);
            result = 1;
        }
    }
    if (n >= 0)
        free(w);
    queue_scan_free(&sq.scan);
    /* a claim held elsewhere: its worker may die before filing it, and a --once worker that left
       would leave it to nobody; it is taken back once judged dead (pid gone, or --lease-timeout) */
    if (result == 0 && any_claim(sq.running, k))
        result = 2;
    if (result == 0 && blocked)
        snprintf(q->waits_requeue, sizeof q->waits_requeue, "%s", stem);
    return result;
}

/* The study in sd is damaged (why): its job file goes from job/ to DIR/failed/ with a log saying what
   is wrong, so that the study ends there, said once; queued again, it is spread anew. */
static void file_damaged(struct queue *q, const char *sd, const char *stem, const char *why)
{
    char job[2400], to[2400], file[300], msg[3000];
    struct stat st;
    snprintf(job, sizeof job, "%s/job", sd);
    if (lstat(job, &st) < 0 || !S_ISDIR(st.st_mode)) /* never through a link */
        return;
    snprintf(file, sizeof file, "%s.yaml", stem);
    snprintf(job, sizeof job, "%s/job/%s", sd, file);
    snprintf(to, sizeof to, "%s/%s", q->failed, file);
    if (lstat(job, &st) < 0 || fileio_rename_noreplace(job, to) < 0)
        return;
    snprintf(msg, sizeof msg, "the study's folder was changed: %s; queue it again to spread it anew", why);
    queue_log(file, "%s; moved to %s/\n", msg, q->failed);
    queue_file_log(q, file, stem, msg, 0, 0);
    queue_file_note_rc(q, 2);
}

/* The recovery lock of a finished study's gather entry, left by a worker killed just after filing
   it (the locks of its other entries were swept at the gather). */
static void sweep_locks(const struct queue *q, const char *sd)
{
    char dir[2400];
    snprintf(dir, sizeof dir, "%s/running", sd);
    lease_sweep_locks(dir, QUEUE_STUDY_GATHER ".lock", q->o->lease_timeout_s);
}

int queue_drain_work(struct queue *q)
{
    char top[1200], sd[2400], why[3000];
    snprintf(top, sizeof top, "%s/%s", q->dir, QUEUE_STUDY_DIR);
    struct stat st;
    if (lstat(top, &st) < 0 || !S_ISDIR(st.st_mode)) /* never through a link (expansion refuses one) */
        return 0;
    DIR *d = opendir(top);
    struct dirent *de;
    int result = 0;
    while (d && result != 1 && (de = readdir(d))) {
        snprintf(sd, sizeof sd, "%s/%s", top, de->d_name);
        if (de->d_name[0] == '.') {
            if (strstr(de->d_name, ".gone."))
                queue_study_remove_tree(sd); /* a discarded study whose remover was killed */
            continue;
        }
        if (lstat(sd, &st) < 0 || !S_ISDIR(st.st_mode) || strlen(de->d_name) > 200)
            continue;
        struct study_key k;
        int r = 0;
        switch (queue_study_state(q->dir, sd, de->d_name, &k, why, sizeof why)) {
        case QUEUE_STUDY_ACTIVE:
        case QUEUE_STUDY_GATHERED: /* only its gather entry to file */
            r = work_on(q, sd, de->d_name, &k);
            break;
        case QUEUE_STUDY_DAMAGED:
            file_damaged(q, sd, de->d_name, why);
            break;
        case QUEUE_STUDY_FINISHED:
            sweep_locks(q, sd);
            break;
        case QUEUE_STUDY_SPREADING: /* its claim is in running/, to be filed in job/ or recovered */
            break;
        }
        queue_study_key_free(&k);
        result = r > result ? r : result;
    }
    if (d)
        closedir(d);
    return result;
}
