/* queue_study: a compare job spread over a queue's workers as one entry per render, gathered once. */
#define _GNU_SOURCE /* nftw's FTW_DEPTH and FTW_PHYS */
#include "queue_study.h"

#include <dirent.h>
#include <fcntl.h>
#include <errno.h>
#include <ftw.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "base/fileio.h"
#include "base/hash.h"
#include "base/sbuf.h"
#include "job/outdir.h"
#include "queue_file.h"
#include "queue_log.h"
#include "queue_study_key.h"
#include "spread_plan.h"
#include "study/run/study_fan.h"

static int remove_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)ftw;
    return flag == FTW_DP ? rmdir(path) : unlink(path);
}

void queue_study_remove_tree(const char *path)
{
    nftw(path, remove_one, 16, FTW_DEPTH | FTW_PHYS);
}

/* Take the study folder at sd out of sight at once (a rename to a hidden name), then remove it. */
static void discard(const struct queue *q, const char *sd, const char *stem)
{
    char gone[2048];
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    snprintf(gone, sizeof gone, "%s/%s/.%s.gone.%ld.%ld", q->dir, QUEUE_STUDY_DIR, stem, (long)getpid(),
             (long)ts.tv_nsec);
    if (rename(sd, gone) == 0)
        queue_study_remove_tree(gone);
}

int queue_study_write_entry(const char *dir, const char *entry, const char *what, struct err *e)
{
    char path[2600], text[512];
    snprintf(path, sizeof path, "%s/%s", dir, entry);
    int n = snprintf(text, sizeof text, "# %s (a render of a study spread over the queue)\n", what);
    return fileio_write_atomic(path, text, (size_t)n, e);
}

/* Write entry into the study folder dir and name it in the record key; its mtime base + rank
   microseconds, so that workers claim the entries in the order written (queue_scan.h: oldest first)
   whatever the file system's clock granularity. */
static int write_entry(const char *dir, struct sbuf *key, const char *entry, const char *what,
                       const struct timespec *base, int rank, struct err *e)
{
    char path[2600];
    queue_study_key_add(key, entry);
    if (queue_study_write_entry(dir, entry, what, e) < 0)
        return -1;
    long long ns = (long long)base->tv_nsec + 1000LL * rank;
    struct timespec t[2] = {{base->tv_sec + (time_t)(ns / 1000000000), ns % 1000000000},
                            {base->tv_sec + (time_t)(ns / 1000000000), ns % 1000000000}};
    snprintf(path, sizeof path, "%s/%s", dir, entry);
    (void)utimensat(AT_FDCWD, path, t, AT_SYMLINK_NOFOLLOW);
    return 0;
}

/* Remove the half-built study folders of job file stem that expanding workers killed before they
   renamed them left: we hold its claim, so no other worker is building one now. */
static void remove_unfinished(const struct queue *q, const char *stem)
{
    char top[1200], prefix[300], path[1600];
    snprintf(top, sizeof top, "%s/%s", q->dir, QUEUE_STUDY_DIR);
    int n = snprintf(prefix, sizeof prefix, ".%s.new.", stem);
    DIR *d = opendir(top);
    struct dirent *de;
    while (d && (de = readdir(d)))
        if (!strncmp(de->d_name, prefix, (size_t)n)) {
            snprintf(path, sizeof path, "%s/%s", top, de->d_name);
            queue_study_remove_tree(path);
        }
    if (d)
        closedir(d);
}

/* Build the study folder of f beside its final place, then rename it there. 0 or -1 with e. */
static int build(const struct queue *q, const struct study_fan *f, const struct spread_plan *p,
                 const char *sd, const char *stem, const uint8_t *job, size_t len, struct err *e)
{
    char tmp[2048], sub[2200], what[512];
    struct sbuf key = {0};
    snprintf(tmp, sizeof tmp, "%s/%s/.%s.new.%ld", q->dir, QUEUE_STUDY_DIR, stem, (long)getpid());
    remove_unfinished(q, stem);
    const char *subs[] = {"job", "running", "done", "failed"};
    if (outdir_mkdirs(tmp, NULL, e) < 0)
        return -1;
    for (int i = 0; i < 4; i++) {
        snprintf(sub, sizeof sub, "%s/%s", tmp, subs[i]);
        if (outdir_mkdirs(sub, NULL, e) < 0)
            goto fail;
    }
    snprintf(sub, sizeof sub, "%s/study.job", tmp);
    if (fileio_write_atomic(sub, job, len, e) < 0)
        goto fail;
    queue_study_key_begin(&key, job, len);
    struct timespec base;
    clock_gettime(CLOCK_REALTIME, &base);
    for (int i = 0; i < p->n; i++) { /* in the plan's order: the critical path's */
        const struct spread_entry *x = &p->e[i];
        const struct compare *c = study_fan_study(f, x->k);
        char part[48] = "";
        if (x->parts > 1)
            snprintf(part, sizeof part, ", row part %d of %d", x->part + 1, x->parts);
        if (x->kind == STUDY_FAN_REFERENCE)
            snprintf(what, sizeof what, "%s: the reference of %s, half %c%s, about %.3g CPU s", c->name,
                     c->scenes[x->index].name, "ab"[x->half], part, x -> est_cpu_s);
        else
            snprintf(what, sizeof what, "%s: %s%s, about %.3g CPU s", c->name, c->items[x->index].job.output,
                     part, x->est_cpu_s);
        if (write_entry(tmp, &key, x->name, what, &base, i, e) < 0)
            goto fail;
    }
    if (write_entry(tmp, &key, QUEUE_STUDY_GATHER, "summary, chart, report and verdict", &base, p->n, e) <
            0 ||
        fileio_write_text(tmp, "study.key", sbuf_take(&key), e) < 0 ||
        fileio_write_text(tmp, SPREAD_PLAN_FILE, spread_plan_text(p), e) < 0)
        goto fail;
    if (rename(tmp, sd) == 0)
        return 0;
    err_set(e, NULL, 0, 0, "cannot make %s: %s", sd, strerror(errno));
fail:
    sbuf_free(&key);
    queue_study_remove_tree(tmp);
    return -1;
}

/* The study folder sd for the job bytes: made, or the one a killed worker left (its record names
   these bytes, every file as written, not yet gathered) taken on. 0, 1 when another study of this
   file name is in progress, -1 with e. */
static int prepare(const struct queue *q, const struct study_fan *f, const struct spread_plan *p,
                   const char *sd, const char *stem, const uint8_t *job, size_t len, struct err *e)
{
    struct stat st;
    if (lstat(sd, &st) == 0) {
        struct study_key k;
        char why[2600];
        enum queue_study_state s = queue_study_state(q->dir, sd, stem, &k, 1, why, sizeof why);
        int same = s == QUEUE_STUDY_SPREADING && k.job_hash == hash_bytes(HASH_FNV_OFFSET, job, len);
        queue_study_key_free(&k);
        char filed[2300];
        snprintf(filed, sizeof filed, "%s/job/%s.yaml", sd, stem);
        /* its job file still filed there (in progress, or damaged: a worker files it in failed/) */
        if (lstat(filed, &st) == 0 || s == QUEUE_STUDY_GATHERED)
            return 1;
        if (same)
            return 0; /* its expanding worker died before filing the job there: carry on */
        discard(q, sd, stem);
    }
    return build(q, f, p, sd, stem, job, len, e);
}

int queue_study_spreading(const struct queue *q, struct lease *holder, char *name, size_t n)
{
    DIR *d = opendir(q->running);
    struct dirent *de;
    int found = 0;
    while (d && !found && (de = readdir(d))) {
        char claim[2048], from[4096], why[512];
        double age;
        if (!queue_scan_is_job_file(de->d_name))
            continue;
        snprintf(claim, sizeof claim, "%s/%s", q->running, de->d_name);
        /* a dead claimer's claim is the recovery's (queue_claim_recover), which the next scan runs */
        if (lease_stale(claim, q->o->lease_timeout_s, why, sizeof why))
            continue;
        queue_claim_source(q, claim, from, sizeof from);
        if (jobfile_peek_kind(from) == JOBFILE_PLAIN)
            continue;
        if (lease_read(claim, holder, &age) < 0) /* claimed this instant: its lease comes next */
            memset(holder, 0, sizeof *holder);
        snprintf(name, n, "%s", de->d_name);
        found = 1;
    }
    if (d)
        closedir(d);
    return found;
}

void queue_study_expand(struct queue *q, const char *name, const struct jobfile *jf, const char *stem)
{
    const char *as = jf->path;
    struct study_fan f;
    struct err e = {0};
    char msg[2600], out[2048], sd[2048], jobdir[2100];
    if (study_fan_load(jf, &f, &e) < 0) {
        err_format(&e, msg, sizeof msg);
        queue_file_invalid(q, name, stem, msg, "invalid compare job", 1);
        return;
    }
    outdir_dir(q->done, study_fan_name(&f), out, sizeof out);
    if (queue_claim_name_owner(q, out, q->name_owner, sizeof q->name_owner)) {
        snprintf(
            msg, sizeof msg,
            "%s: name: \"%s\" is taken: %s/ holds the outputs of %s; give this job another name (or remove "
            "that folder to replace them)",
            as, study_fan_name(&f), out, q->name_owner);
        queue_file_invalid(q, name, stem, msg, "invalid compare job", 1);
        study_fan_free(&f);
        return;
    }
    snprintf(sd, sizeof sd, "%s/%s/%s", q->dir, QUEUE_STUDY_DIR, stem);
    snprintf(jobdir, sizeof jobdir, "%s/job", sd);
    snprintf(msg, sizeof msg, "%s/%s", q->dir, QUEUE_STUDY_DIR);
    struct spread_plan plan = {0};
    int rc = outdir_check(out, &e) < 0 || outdir_mkdirs(msg, NULL, &e) < 0 ||
                     spread_plan_make(&f, q->o->entry_cpu_s > 0 ? q->o->entry_cpu_s : SPREAD_PLAN_ENTRY_CPU_S,
                                      q->o->run.processes, &plan, &e) < 0
                 ? -1
                 : prepare(q, &f, &plan, sd, stem, jf->bytes, jf->len, &e);
    if (rc < 0 && outdir_env_error(&e)) {
        queue_file_env_stop(q, name, &e);
    } else if (rc < 0) {
        err_prefix(&e, study_fan_name(&f));
        err_format(&e, msg, sizeof msg);
        queue_file_invalid(q, name, study_fan_name(&f), msg, "invalid compare job", 1);
    } else if (rc == 1) {
        snprintf(msg, sizeof msg,
                 "%s: a study of this file name is in progress in %s/; queue it again when it is done", as,
                 sd);
        queue_file_invalid(q, name, stem, msg, "invalid compare job", 1);
    } else {
        int refs = 0;
        for (int i = 0; i < plan.n; i++)
            refs += plan.e[i].kind == STUDY_FAN_REFERENCE;
        queue_claim_file(q, name, jobdir);
        queue_log(name,
                  "spread over the queue: %d entr%s (%d of references, %d of images; about %.3g CPU s in "
                  "all), then the gather, in %s/\n",
                  plan.n, plan.n == 1 ? "y" : "ies", refs, plan.n - refs, plan.total_cpu_s, sd);
    }
    spread_plan_free(&plan);
    study_fan_free(&f);
}
