/* queue_status: what a queue holds (status). */
#include "queue_status.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/err.h"
#include "base/fileio.h"
#include "base/json.h"
#include "job/outdir.h"
#include "job/sidecar.h"
#include "lease.h"
#include "queue_scan.h"
#include "queue_status_print.h"
#include "queue_studies.h"
#include "queue_study.h"
#include "scenefile/yamlx.h"

void queue_status_job_name(const char *path, const char *file, char *out, size_t n)
{
    struct ydoc d;
    struct err e;
    outdir_stem(file, out, n);
    if (ydoc_load(&d, path, &e) == 0) {
        yaml_node_t *root = ydoc_root(&d);
        const char *s = root && root->type == YAML_MAPPING_NODE ? yscalar(ymap_get(&d, root, "name")) : NULL;
        if (s && *s && s[0] != '.' && !strchr(s, '/'))
            snprintf(out, n, "%s", s);
    }
    ydoc_free(&d);
}

/* Add to x the sidecars in folder whose job file is `file` (NULL: any), and, at the top (depth 0),
   those in its subfolders: a suite's studies, whose images name their study's file. */
static void sum_sidecars(const char *folder, const char *file, int depth, struct status_entry *x)
{
    DIR *dir = opendir(folder);
    if (!dir)
        return;
    struct dirent *de;
    while ((de = readdir(dir))) {
        size_t len = strlen(de->d_name);
        char path[4096];
        struct sidecar_info info;
        struct err e;
        struct stat st;
        snprintf(path, sizeof path, "%s/%s", folder, de->d_name);
        if (de->d_name[0] == '.')
            continue;
        if (depth == 0 && lstat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
            sum_sidecars(path, NULL, 1, x);
            continue;
        }
        if (len < 6 || strcmp(de->d_name + len - 5, ".json") || sidecar_read(path, &info, &e) < 0)
            continue;
        const char *jf = info.job_file, *base = strrchr(jf, '/') ? strrchr(jf, '/') + 1 : jf;
        if ((!file || !strcmp(base, file)) && isfinite(info.wall_s) && isfinite(info.cpu_s)) {
            x->wall_s = (x->images ? x->wall_s : 0) + info.wall_s; /* a compare job's images: summed */
            x->cpu_s = (x->images ? x->cpu_s : 0) + info.cpu_s;
            x->samples = (x->images ? x->samples : 0) + (double)info.samples_total;
            x->images++;
        }
    }
    closedir(dir);
}

/* Fill x's wall, CPU and samples from the sidecars in done/<name>/ made from x's job file. */
static void read_sidecar(const char *done, struct status_entry *x)
{
    char folder[2048], file[1024];
    snprintf(folder, sizeof folder, "%s/%s", done, x->name);
    x->wall_s = x->cpu_s = x->samples = -1;
    if (json_string_read_back(x->file, file, sizeof file) == 0) /* as a sidecar records it */
        sum_sidecars(folder, file, 0, x);
}

/* The first line of the error in failed/<name>.log (or <stem>.log) into x->reason. */
static void read_reason(const char *failed, struct status_entry *x)
{
    char path[2048], stem[256];
    uint8_t *text = NULL;
    size_t len;
    struct err e;
    outdir_stem(x->file, stem, sizeof stem);
    const char *log_names[] = {x->name, stem};
    for (int i = 0; i < 2 && !text; i++) { /* fileio_read_all leaves text NULL when it fails */
        snprintf(path, sizeof path, "%s/%s.log", failed, log_names[i]);
        (void)fileio_read_all(path, 1 << 20, &text, &len, &e);
    }
    const char *s = text ? strstr((const char *)text, "error: ") : NULL;
    s = s ? s + strlen("error: ") : "(no log)";
    snprintf(x->reason, sizeof x->reason, "%.*s", (int)strcspn(s, "\n"), s);
    free(text);
}

static int by_when(const void *pa, const void *pb)
{
    const struct status_entry *a = pa, *b = pb;
    if (a->when.tv_sec != b->when.tv_sec)
        return a->when.tv_sec < b->when.tv_sec ? -1 : 1;
    return strcmp(a->file, b->file);
}

/* The job files X.yaml of folder dir (running/, done/ or failed/) into *out, by time. */
static int list_folder(const char *dir, const char *kind, const char *done, struct status_entry **out)
{
    DIR *d = opendir(dir);
    struct status_entry *v = NULL;
    int n = 0;
    *out = NULL;
    if (!d)
        return errno == ENOENT ? 0 : -1;
    struct dirent *de;
    while ((de = readdir(d))) {
        char path[2048];
        struct stat st;
        if (!queue_scan_is_job_file(de->d_name) || strlen(de->d_name) >= sizeof v->file)
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        if (lstat(path, &st) < 0)
            continue;
        struct status_entry *g = realloc(v, (size_t)(n + 1) * sizeof *v);
        if (!g)
            break;
        v = g;
        struct status_entry *x = &v[n++];
        memset(x, 0, sizeof *x);
        snprintf(x->file, sizeof x->file, "%s", de->d_name);
        x->when = st.st_ctim; /* the rename into this folder */
        queue_status_job_name(path, x->file, x->name, sizeof x->name);
        if (!strcmp(kind, "done"))
            read_sidecar(done, x);
        else if (!strcmp(kind, "failed"))
            read_reason(dir, x);
        else if (lease_read(path, &x->lease, &x->age_s) < 0)
            x->age_s = -1;
        else { /* a worker this host knows to be dead; another host's is judged by lease age, at a
                  timeout only workers know: not said here */
            char why[256];
            x->gone = lease_stale(path, 1e30, why, sizeof why);
        }
    }
    closedir(d);
    if (n > 1)
        qsort(v, (size_t)n, sizeof *v, by_when);
    *out = v;
    return n;
}

/* 1 when dir may be a queue: it holds a folder a queue worker makes (running/, done/, failed/ or
   spread/), or nothing at all (a queue no worker has seen yet); 0 for a folder of other things (an
   output folder of --out: its <name>/ and .cache/). */
static int queue_status_is_queue(const char *dir)
{
    const char *own[] = {"running", "done", "failed", QUEUE_STUDY_DIR};
    for (int i = 0; i < 4; i++)
        if (queue_scan_has(dir, own[i]))
            return 1;
    DIR *d = opendir(dir);
    struct dirent *de;
    int empty = 1;
    while (d && empty && (de = readdir(d)))
        empty = !strcmp(de->d_name, ".") || !strcmp(de->d_name, "..");
    if (d)
        closedir(d);
    return empty;
}

int queue_status_dir(const char *who, const char *arg, char *out, size_t n)
{
    struct stat st;
    snprintf(out, n, "%s", arg);
    for (size_t l = strlen(out); l > 1 && out[l - 1] == '/'; l--)
        out[l - 1] = 0;
    int bad = stat(out, &st) < 0 ? errno : S_ISDIR(st.st_mode) ? 0 : ENOTDIR;
    if (bad)
        err_print("%s%s: %s\n", who, out, strerror(bad));
    return bad ? 2 : 0;
}

int queue_status_main(int argc, char **argv)
{
    const char *dir_arg = NULL;
    int json = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--json"))
            json = 1;
        else if (!strcmp(argv[i], "--quiet"))
            continue;
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h"))
            return printf("usage: worker status DIR [--json]\nthe queue's jobs: waiting, running (progress, "
                          "ETA), done (figures), failed (why)\n") < 0;
        else if (argv[i][0] == '-' && argv[i][1]) {
            err_print("worker status: unknown option %s; usage: worker status DIR [--json]\n", argv[i]);
            return 2;
        } else if (dir_arg) {
            err_print("worker status: one queue directory, got a second: %s\n", argv[i]);
            return 2;
        } else
            dir_arg = argv[i];
    }
    char dir[1024], sub[1100];
    if (!dir_arg) {
        err_print("worker status: expected a queue directory; usage: worker status DIR [--json]\n");
        return 2;
    }
    if (queue_status_dir("worker status: ", dir_arg, dir, sizeof dir))
        return 2;
    struct queue_scan scan = {0};
    struct queue_waiting *w = NULL;
    struct status_entry *lists[3] = {NULL};
    struct queue_studies_entry *studies = NULL;
    int nw = queue_scan_waiting(&scan, dir, &w), rc = 0, counts[3];
    char done[1100];
    snprintf(done, sizeof done, "%s/done", dir);
    const char *bad = nw < 0 && errno != ENOENT ? "." : NULL, *folders[] = {"running", "done", "failed"};
    int bad_errno = errno;
    for (int i = 0; i < 3; i++) {
        snprintf(sub, sizeof sub, "%s/%s", dir, folders[i]);
        if ((counts[i] = list_folder(sub, folders[i], done, &lists[i])) < 0)
            bad = folders[i], bad_errno = errno;
    }
    int ns = queue_studies_list(dir, &studies);
    if (ns < 0)
        bad = QUEUE_STUDY_DIR, bad_errno = errno;
    if (!bad && nw <= 0 && !queue_status_is_queue(dir)) {
        err_print("worker status: %s: not a queue: it holds other things but no running/, done/ or failed/ "
                  "folder and no job file X.yaml waiting (an output folder of --out? worker --queue %s "
                  "makes a queue of it)\n",
                  dir, dir);
        rc = 2;
    } else if (bad) { /* a folder that cannot be read is no empty one: "0 failed" would be a lie */
        err_print("worker status: %s/%s: cannot be read: %s\n", dir, bad, strerror(bad_errno));
        rc = 2;
    } else {
        struct status_view v = {w,         lists[0],  lists[1],  lists[2],        nw < 0 ? 0 : nw,
                                counts[0], counts[1], counts[2], ns < 0 ? 0 : ns, studies};
        if (json)
            queue_status_print_json(dir, &v);
        else
            queue_status_print_text(dir, &v);
    }
    free(w);
    for (int i = 0; i < 3; i++)
        free(lists[i]);
    free(studies);
    queue_scan_free(&scan);
    return rc;
}
