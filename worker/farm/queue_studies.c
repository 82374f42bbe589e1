/* queue_studies: studies in progress in a queue, for status and requeue. */
#include "queue_studies.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "base/err.h"
#include "base/fileio.h"
#include "queue_study.h"
#include "queue_study_key.h"
#include "spread_plan.h"

/* The study's render entries (a-*, b-*: not the gather) in folder dir, those its record k names;
   the gather's presence into *gather. */
static int count_entries(const char *dir, const struct study_key *k, int *gather)
{
    DIR *d = opendir(dir);
    struct dirent *de;
    int n = 0;
    while (d && (de = readdir(d))) {
        if (!queue_study_key_has(k, de->d_name))
            continue;
        if (!strcmp(de->d_name, QUEUE_STUDY_GATHER))
            *gather = 1;
        else
            n++;
    }
    if (d)
        closedir(d);
    return n;
}

/* Leases held in folder dir (a queue's or a study's running/). */
static int leases_in(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *de;
    int n = 0;
    while (d && (de = readdir(d))) {
        size_t len = strlen(de->d_name);
        n += len > 6 && !strcmp(de->d_name + len - 6, ".lease");
    }
    if (d)
        closedir(d);
    return n;
}

/* The study's CPU done and left by its plan (sd/plan.txt; none for a study spread before it was
   written), and its predicted finish: the entries not done, in claim order, on the workers that
   hold a lease now (`workers`), each of this machine's cores. */
static void read_plan(const char *sd, int workers, struct queue_studies_entry *x)
{
    char path[2400];
    struct spread_plan p;
    snprintf(path, sizeof path, "%s/%s", sd, SPREAD_PLAN_FILE);
    x->finish_s = -1;
    if (spread_plan_read(path, &p) < 0)
        return;
    int left = 0;
    for (int i = 0; i < p.n; i++) {
        snprintf(path, sizeof path, "%s/done", sd);
        if (queue_scan_has(path, p.e[i].name)) {
            x->cpu_done_s += p.e[i].est_cpu_s;
        } else {
            x->cpu_left_s += p.e[i].est_cpu_s;
            p.e[left++] = p.e[i]; /* kept in claim order */
        }
    }
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    x->planned = 1;
    x->lease_workers = workers;
    if (left == 0)
        x->finish_s = 0;
    else if (workers > 0)
        x->finish_s = spread_plan_makespan(p.e, left, workers, cores > 0 ? (int)cores : 1);
    spread_plan_free(&p);
}

/* The study folder sd's progress into x; 0, or -1 when it is no study in progress (being spread,
   or finished). A damaged one is shown with what is wrong. */
static int read_study(const char *dir, const char *sd, const char *stem, int workers,
                      struct queue_studies_entry *x)
{
    char sub[2300];
    struct stat st;
    struct study_key k;
    int waiting_gather = 0, running_gather = 0, done_gather = 0, failed_gather = 0;
    memset(x, 0, sizeof *x);
    enum queue_study_state state = queue_study_state(dir, sd, stem, &k, 1, x->damaged, sizeof x->damaged);
    if (state == QUEUE_STUDY_SPREADING || state == QUEUE_STUDY_FINISHED) {
        queue_study_key_free(&k);
        return -1;
    }
    if (state != QUEUE_STUDY_DAMAGED)
        x->damaged[0] = 0;
    snprintf(x->name, sizeof x->name, "%s", stem);
    snprintf(x->file, sizeof x->file, "%s.yaml", stem);
    int waiting = count_entries(sd, &k, &waiting_gather);
    snprintf(sub, sizeof sub, "%s/running", sd);
    x->running = count_entries(sub, &k, &running_gather);
    snprintf(sub, sizeof sub, "%s/done", sd);
    x->done = count_entries(sub, &k, &done_gather);
    snprintf(sub, sizeof sub, "%s/failed", sd);
    x->failed = count_entries(sub, &k, &failed_gather);
    queue_study_key_free(&k);
    x->failed += failed_gather;
    x->gathering = running_gather;
    x->renders = waiting + x->running + x->done + x->failed - failed_gather;
    snprintf(sub, sizeof sub, "%s/study.job", sd);
    x->elapsed_s = lstat(sub, &st) == 0 ? difftime(time(NULL), st.st_mtim.tv_sec) : 0;
    /* a failed render blocks the gather: no pace tells when a requeue comes */
    x->waits_requeue = x->failed > 0;
    x->eta_s = x->done > 0 && x->elapsed_s >= 0 && !x->waits_requeue && !x->damaged[0]
                   ? x->elapsed_s * (x->renders - x->done) / x->done
                   : -1;
    read_plan(sd, workers, x);
    return 0;
}

static int by_name(const void *pa, const void *pb)
{
    return strcmp(((const struct queue_studies_entry *)pa)->name,
                  ((const struct queue_studies_entry *)pb)->name);
}

int queue_studies_list(const char *dir, struct queue_studies_entry **out)
{
    char top[1200], sd[1600];
    snprintf(top, sizeof top, "%s/%s", dir, QUEUE_STUDY_DIR);
    *out = NULL;
    DIR *d = opendir(top);
    if (!d)
        return errno == ENOENT ? 0 : -1;
    struct dirent *de;
    struct queue_studies_entry *v = NULL, x;
    int n = 0;
    snprintf(sd, sizeof sd, "%s/running", dir);
    int workers = leases_in(sd); /* a worker holds one lease at a time: the queue's and its studies' */
    while ((de = readdir(d))) {
        snprintf(sd, sizeof sd, "%s/%s/running", top, de->d_name);
        if (de->d_name[0] != '.' && strlen(de->d_name) <= 200)
            workers += leases_in(sd);
    }
    rewinddir(d);
    while ((de = readdir(d))) {
        if (de->d_name[0] == '.' || strlen(de->d_name) > 200)
            continue;
        snprintf(sd, sizeof sd, "%s/%s", top, de->d_name);
        if (read_study(dir, sd, de->d_name, workers, &x) < 0)
            continue;
        struct queue_studies_entry *g = realloc(v, (size_t)(n + 1) * sizeof *v);
        if (!g)
            break;
        v = g;
        v[n++] = x;
    }
    closedir(d);
    if (n > 1)
        qsort(v, (size_t)n, sizeof *v, by_name);
    *out = v;
    return n;
}

/* Put the failed entry sd/failed/name back among the study's waiting entries: moved when it is a
   regular file; written anew when it is not (a FIFO, a folder, a link put in its place), the other
   thing removed. 0, 1 when another requeue (or a worker) moved it first, -1 with errno. */
static int put_back(const char *sd, const char *name)
{
    char from[2400], to[2400], fresh[2400];
    struct stat st;
    struct err e;
    snprintf(from, sizeof from, "%s/failed/%s", sd, name);
    snprintf(to, sizeof to, "%s/%s", sd, name);
    if (lstat(from, &st) < 0)
        return errno == ENOENT ? 1 : -1;
    if (S_ISREG(st.st_mode))
        return fileio_rename_noreplace(from, to) == 0 ? 0 : errno == ENOENT ? 1 : -1;
    snprintf(fresh, sizeof fresh, "%s/failed/.%s.new.%ld", sd, name, (long)getpid());
    if (queue_study_write_entry(sd, fresh + strlen(sd) + 1, "requeued", &e) < 0) {
        errno = e.errnum ? e.errnum : EIO;
        return -1;
    }
    if (fileio_rename_noreplace(fresh, to) < 0) {
        int saved = errno;
        unlink(fresh);
        errno = saved;
        return errno == EEXIST ? 1 : -1;
    }
    queue_study_remove_tree(from); /* never follows a link: a folder's own files only */
    return 0;
}

int queue_studies_requeue(const char *dir, const char *file)
{
    char sd[1600], failed[1700], from[2000], why[1200];
    struct study_key k;
    size_t len = strlen(file);
    if (len < 6 || len > 200)
        return -1;
    snprintf(sd, sizeof sd, "%s/%s/%.*s", dir, QUEUE_STUDY_DIR, (int)(len - 5), file);
    snprintf(from, sizeof from, "%.*s", (int)(len - 5), file);
    enum queue_study_state state = queue_study_state(dir, sd, from, &k, 1, why, sizeof why);
    if (state != QUEUE_STUDY_ACTIVE) {
        queue_study_key_free(&k);
        return -1;
    }
    snprintf(failed, sizeof failed, "%s/failed", sd);
    DIR *d = opendir(failed);
    if (!d) {
        err_print("worker requeue: %s: %s: %s\n", file, failed, strerror(errno));
        queue_study_key_free(&k);
        return -2;
    }
    struct dirent *de;
    int moved = 0, bad = 0;
    while ((de = readdir(d))) {
        if (!queue_study_key_has(&k, de->d_name)) /* what the study never wrote stays where it is */
            continue;
        int r = put_back(sd, de->d_name);
        if (r < 0) {
            err_print("worker requeue: %s: %s: %s\n", file, de->d_name, strerror(errno));
            bad = 1;
        }
        if (r != 0)
            continue;
        snprintf(from, sizeof from, "%s/%.*s.log", failed, (int)(strlen(de->d_name) - 5), de->d_name);
        unlink(from);
        moved++;
    }
    closedir(d);
    queue_study_key_free(&k);
    if (!bad)
        err_print("%s: %d failed render%s of the study requeued\n", file, moved, moved == 1 ? "" : "s");
    return bad ? -2 : moved;
}
