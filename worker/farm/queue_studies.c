/* queue_studies: studies in progress in a queue, for status and requeue. */
#include "queue_studies.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "base/err.h"
#include "base/fileio.h"
#include "base/sbuf.h"
#include "queue_scan.h"
#include "queue_study.h"

/* Render entries (a-*, b-*: not the gather) of folder dir; the gather's presence into *gather. */
static int count_entries(const char *dir, int *gather)
{
    DIR *d = opendir(dir);
    struct dirent *de;
    int n = 0;
    while (d && (de = readdir(d))) {
        if (!queue_scan_is_job_file(de->d_name))
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

/* The study folder sd's progress into x; 0, or -1 when it is no study in progress. */
static int read_study(const char *sd, const char *stem, struct queue_studies_entry *x)
{
    char sub[2300];
    struct stat st;
    int waiting_gather = 0, running_gather = 0, done_gather = 0, failed_gather = 0;
    snprintf(sub, sizeof sub, "%s/study.job", sd);
    if (lstat(sub, &st) < 0 || !S_ISREG(st.st_mode))
        return -1;
    memset(x, 0, sizeof *x);
    snprintf(x->name, sizeof x->name, "%s", stem);
    snprintf(x->file, sizeof x->file, "%s.yaml", stem);
    int waiting = count_entries(sd, &waiting_gather);
    snprintf(sub, sizeof sub, "%s/running", sd);
    x->running = count_entries(sub, &running_gather);
    snprintf(sub, sizeof sub, "%s/done", sd);
    x->done = count_entries(sub, &done_gather);
    snprintf(sub, sizeof sub, "%s/failed", sd);
    x->failed = count_entries(sub, &failed_gather);
    if (done_gather)
        return -1; /* finished: its job file is in done/ */
    x->failed += failed_gather;
    x->gathering = running_gather;
    x->renders = waiting + x->running + x->done + x->failed - failed_gather;
    x->elapsed_s = difftime(time(NULL), st.st_mtim.tv_sec);
    x->eta_s = x->done > 0 && x->elapsed_s >= 0 ? x->elapsed_s * (x->renders - x->done) / x->done : -1;
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
    while ((de = readdir(d))) {
        if (de->d_name[0] == '.' || strlen(de->d_name) > 200)
            continue;
        snprintf(sd, sizeof sd, "%s/%s", top, de->d_name);
        if (read_study(sd, de->d_name, &x) < 0)
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

void queue_studies_print(const struct queue_studies_entry *s, int n)
{
    if (n)
        printf("studies (spread over the queue):\n");
    for (int i = 0; i < n; i++) {
        char eta[32] = "--";
        if (s[i].eta_s >= 0)
            snprintf(eta, sizeof eta, "%.0f s", s[i].eta_s);
        char file[4 * sizeof s[i].file + 1], name[4 * sizeof s[i].name + 1]; /* shown, never raw */
        printf("  %s  study %s  %d/%d renders done, %d failed, %d running%s  elapsed %.0f s  ETA %s\n",
               sbuf_show(s[i].file, file, sizeof file), sbuf_show(s[i].name, name, sizeof name), s[i].done,
               s[i].renders, s[i].failed, s[i].running, s[i].gathering ? ", gathering" : "", s[i].elapsed_s,
               s[i].done == s[i].renders ? "0 s" : eta);
    }
}

void queue_studies_json(struct json *js, const struct queue_studies_entry *s, int n)
{
    json_begin_array(js, "studies");
    for (int i = 0; i < n; i++) {
        json_begin_object(js, NULL);
        json_string(js, "file", s[i].file);
        json_string(js, "name", s[i].name);
        json_number(js, "renders", s[i].renders);
        json_number(js, "done", s[i].done);
        json_number(js, "failed", s[i].failed);
        json_number(js, "running", s[i].running);
        json_bool(js, "gathering", s[i].gathering);
        json_number(js, "elapsed_s", s[i].elapsed_s);
        json_number(js, "eta_s", s[i].eta_s < 0 ? (double)NAN : s[i].eta_s);
        json_end_object(js);
    }
    json_end_array(js);
}

int queue_studies_requeue(const char *dir, const char *file)
{
    char sd[1600], failed[1700], from[2000], to[2000];
    struct stat st;
    size_t len = strlen(file);
    if (len < 6 || len > 200)
        return -1;
    snprintf(sd, sizeof sd, "%s/%s/%.*s", dir, QUEUE_STUDY_DIR, (int)(len - 5), file);
    snprintf(from, sizeof from, "%s/job/%s", sd, file);
    if (lstat(from, &st) < 0)
        return -1;
    snprintf(failed, sizeof failed, "%s/failed", sd);
    DIR *d = opendir(failed);
    if (!d) {
        err_print("worker requeue: %s: %s: %s\n", file, failed, strerror(errno));
        return -2;
    }
    struct dirent *de;
    int moved = 0, bad = 0;
    while ((de = readdir(d))) {
        if (!queue_scan_is_job_file(de->d_name))
            continue;
        snprintf(from, sizeof from, "%s/%s", failed, de->d_name);
        snprintf(to, sizeof to, "%s/%s", sd, de->d_name);
        if (fileio_rename_noreplace(from, to) < 0) {
            if (errno != ENOENT) { /* ENOENT: another requeue moved it first */
                err_print("worker requeue: %s: %s: %s\n", file, de->d_name, strerror(errno));
                bad = 1;
            }
            continue;
        }
        snprintf(from, sizeof from, "%s/%.*s.log", failed, (int)(strlen(de->d_name) - 5), de->d_name);
        unlink(from);
        moved++;
    }
    closedir(d);
    if (!bad)
        err_print("%s: %d failed render%s of the study requeued\n", file, moved, moved == 1 ? "" : "s");
    return bad ? -2 : moved;
}
