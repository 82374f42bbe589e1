/* queue_requeue: `worker requeue DIR NAME... | --failed`: failed (or done) job files moved back into
   the queue, and a study's failed renders back to its waiting entries. */
#include "queue_requeue.h"

#include <dirent.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/err.h"
#include "base/fileio.h"
#include "job/outdir.h"
#include "queue_scan.h"
#include "queue_status.h"
#include "queue_studies.h"

/* scandir's filter: the job files X.yaml. */
static int is_job_entry(const struct dirent *de)
{
    return queue_scan_is_job_file(de->d_name);
}

/* The job file failed/<name>.log's "job:" line names (a failed job's log is named for its job's
   name:, which may differ from its file's stem): into file; 0, or -1 without such a log. */
static int file_of_log(const char *failed, const char *name, char *file, size_t n)
{
    char path[2048];
    uint8_t *text = NULL;
    size_t len;
    struct err e;
    snprintf(path, sizeof path, "%s/%s.log", failed, name);
    if (fileio_read_all(path, 1 << 20, &text, &len, &e) < 0)
        return -1;
    const char *t = (const char *)text;
    size_t line = strcspn(t, "\n"), base = line;
    while (base > 0 && t[base - 1] != '/')
        base--;
    int ok = !strncmp(t, "job: ", 5) && base > 5 && line - base > 0 && line - base < n;
    if (ok)
        snprintf(file, n, "%.*s", (int)(line - base), t + base);
    free(text);
    return ok ? 0 : -1;
}

/* Remove DIR/failed/<log_name>.log when it is the log of job file `file` (its "job:" line names it). */
static void remove_log(const char *dir, const char *log_name, const char *file)
{
    char failed[2048], named[256], path[2400];
    snprintf(failed, sizeof failed, "%s/failed", dir);
    if (file_of_log(failed, log_name, named, sizeof named) == 0 && !strcmp(named, file)) {
        snprintf(path, sizeof path, "%s/%s.log", failed, log_name);
        unlink(path);
    }
}

/* Move DIR/<from>/<file> back to DIR/<file>; 0, or -1 after one line. Under --failed (every), a
   file another requeue moved first is no error: every failed job is requeued all the same. */
static int requeue_one(const char *dir, const char *from, const char *file, int every)
{
    char src[2048], dst[2048], running[2048];
    snprintf(src, sizeof src, "%s/%s/%s", dir, from, file);
    snprintf(dst, sizeof dst, "%s/%s", dir, file);
    snprintf(running, sizeof running, "%s/running", dir);
    if (queue_scan_has(running, file)) {
        err_print("worker requeue: %s: a job of that file name is running; left in %s/\n", file, from);
        return -1;
    }
    char name[256], stem[256];
    /* its name read before the move: once moved, a worker may claim it at once */
    queue_status_job_name(src, file, name, sizeof name);
    outdir_stem(file, stem, sizeof stem);
    if (fileio_rename_noreplace(src, dst) < 0) {
        if (every && errno == ENOENT)
            return 0;
        err_print("worker requeue: %s: %s\n", file,
                  errno == EEXIST   ? "a job of that file name waits in the queue already"
                  : errno == ENOENT ? "no longer there: moved meanwhile (another requeue, or a worker)"
                                    : strerror(errno));
        return -1;
    }
    if (!strcmp(from, "failed")) { /* its log goes with it: it is no longer a failed job */
        remove_log(dir, name, file);
        remove_log(dir, stem, file); /* the log of a file that did not load, or whose name was taken */
    }
    err_print("%s: requeued from %s/\n", file, from);
    return 0;
}

int queue_requeue_main(int argc, char **argv)
{
    const char *dir_arg = NULL;
    int all_failed = 0, nnames = 0, rc = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--failed"))
            all_failed = 1;
        else if (!strcmp(argv[i], "--quiet"))
            continue;
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: worker requeue DIR NAME... | --failed\n"
                   "put the named jobs of queue DIR (from failed/ or done/) back to wait, or every failed "
                   "one\n");
            return 0;
        } else if (argv[i][0] == '-' && argv[i][1]) {
            err_print("worker requeue: unknown option %s; usage: worker requeue DIR NAME... | --failed\n",
                      argv[i]);
            return 2;
        } else if (!dir_arg)
            dir_arg = argv[i];
        else
            nnames++;
    }
    if (!dir_arg || (nnames == 0) == !all_failed) {
        err_print("worker requeue: usage: worker requeue DIR NAME... | --failed\n");
        return 2;
    }
    char dir[1024], failed[1100], done[1100];
    if (queue_status_dir("worker requeue: ", dir_arg, dir, sizeof dir))
        return 2;
    snprintf(failed, sizeof failed, "%s/failed", dir);
    snprintf(done, sizeof done, "%s/done", dir);
    if (all_failed) {
        struct queue_studies_entry *studies;
        struct dirent **files = NULL;
        /* by name: alphasort's strcoll is strcmp, the program setting no locale */
        int nf = scandir(failed, &files, is_job_entry, alphasort);
        if (nf < 0 && errno == ENOENT)
            nf = 0;
        if (nf < 0) {
            err_print("worker requeue: %s: cannot be read: %s\n", failed, strerror(errno));
            return 2;
        }
        for (int i = 0; i < nf; i++) {
            if (requeue_one(dir, "failed", files[i]->d_name, 1) < 0)
                rc = 2;
            free(files[i]);
        }
        free(files);
        int ns = queue_studies_list(dir, &studies);
        for (int i = 0; i < ns; i++)
            if (studies[i].failed && queue_studies_requeue(dir, studies[i].file) == -2)
                rc = 2;
        free(studies);
        return rc;
    }
    for (int i = 1, seen_dir = 0; i < argc; i++) {
        if (argv[i][0] == '-' && argv[i][1])
            continue;
        if (!seen_dir++)
            continue;
        char file[256];
        size_t len = strlen(argv[i]);
        if (strchr(argv[i], '/') || len == 0 || len > 200) {
            err_print("worker requeue: %s: give a job file's name (X or X.yaml), not a path\n", argv[i]);
            rc = 2;
            continue;
        }
        snprintf(file, sizeof file, "%s%s", argv[i],
                 len > 5 && !strcmp(argv[i] + len - 5, ".yaml") ? "" : ".yaml");
        int study = queue_studies_requeue(dir, file); /* a study in progress: its failed renders */
        if (study != -1) {
            rc = study == -2 ? 2 : rc;
            continue;
        }
        const char *from = queue_scan_has(failed, file) ? "failed"
                           : queue_scan_has(done, file) ? "done"
                                                        : NULL;
        if (!from && file_of_log(failed, argv[i], file, sizeof file) == 0) /* a job's name: its log's file */
            from = queue_scan_has(failed, file) ? "failed" : NULL;
        if (!from) {
            err_print("worker requeue: %s: not in %s/failed/ or %s/done/\n", file, dir, dir);
            rc = 2;
        } else if (requeue_one(dir, from, file, 0) < 0)
            rc = 2;
    }
    return rc;
}
