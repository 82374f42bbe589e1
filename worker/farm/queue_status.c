/* queue_status: what a queue holds (status). */
#include "queue_status.h"

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
#include "base/json.h"
#include "job/outdir.h"
#include "job/sidecar.h"
#include "lease.h"
#include "queue_scan.h"
#include "queue_studies.h"
#include "queue_study.h"
#include "scenefile/yamlx.h"

/* One job file of done/ or failed/ (or running/), with what status says about it. */
struct entry {
    char file[256];
    char name[256]; /* the job's name: its `name:`, else the file's stem */
    struct timespec when;
    double wall_s, cpu_s, samples; /* done: from the sidecar (a compare job's: summed); < 0 unknown */
    int images;                    /* done: sidecars summed */
    char reason[512];              /* failed: the log's error, first line */
    struct lease lease;            /* running */
    double age_s;                  /* running: seconds since the lease was renewed; < 0 no lease */
};

static void iso8601(time_t t, char *out, size_t n)
{
    struct tm tm;
    gmtime_r(&t, &tm);
    strftime(out, n, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

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

/* Fill x's wall, CPU and samples from the sidecar in done/<name>/ made from x's job file. */
static void read_sidecar(const char *done, struct entry *x)
{
    char folder[2048];
    snprintf(folder, sizeof folder, "%s/%s", done, x->name);
    x->wall_s = x->cpu_s = x->samples = -1;
    char file[1024];
    if (json_string_read_back(x->file, file, sizeof file) < 0) /* as a sidecar records it */
        return;
    DIR *dir = opendir(folder);
    if (!dir)
        return;
    struct dirent *de;
    while ((de = readdir(dir))) {
        size_t len = strlen(de->d_name);
        if (de->d_name[0] == '.' || len < 6 || strcmp(de->d_name + len - 5, ".json"))
            continue;
        char path[4096];
        struct sidecar_info info;
        struct err e;
        snprintf(path, sizeof path, "%s/%s", folder, de->d_name);
        if (sidecar_read(path, &info, &e) == 0) { /* a compare job's images: summed */
            const char *jf = info.job_file, *base = strrchr(jf, '/') ? strrchr(jf, '/') + 1 : jf;
            if (!strcmp(base, file) && isfinite(info.wall_s) && isfinite(info.cpu_s)) {
                x->wall_s = (x->images ? x->wall_s : 0) + info.wall_s;
                x->cpu_s = (x->images ? x->cpu_s : 0) + info.cpu_s;
                x->samples = (x->images ? x->samples : 0) + (double)info.samples_total;
                x->images++;
            }
        }
    }
    closedir(dir);
}

/* The first line of the error in failed/<name>.log (or <stem>.log) into x->reason. */
static void read_reason(const char *failed, struct entry *x)
{
    char path[2048];
    uint8_t *text = NULL;
    size_t len;
    struct err e;
    snprintf(path, sizeof path, "%s/%s.log", failed, x->name);
    if (fileio_read_all(path, 1 << 20, &text, &len, &e) < 0) {
        char stem[256];
        outdir_stem(x->file, stem, sizeof stem);
        snprintf(path, sizeof path, "%s/%s.log", failed, stem);
        if (fileio_read_all(path, 1 << 20, &text, &len, &e) < 0)
            text = NULL;
    }
    const char *s = text ? strstr((const char *)text, "error: ") : NULL;
    if (s) {
        s += strlen("error: ");
        snprintf(x->reason, sizeof x->reason, "%.*s", (int)strcspn(s, "\n"), s);
    } else
        snprintf(x->reason, sizeof x->reason, "(no log)");
    free(text);
}

static int by_when(const void *pa, const void *pb)
{
    const struct entry *a = pa, *b = pb;
    if (a->when.tv_sec != b->when.tv_sec)
        return a->when.tv_sec < b->when.tv_sec ? -1 : 1;
    return strcmp(a->file, b->file);
}

/* The job files X.yaml of folder dir (running/, done/ or failed/) into *out, by time. */
static int list_folder(const char *dir, const char *kind, const char *done, struct entry **out)
{
    DIR *d = opendir(dir);
    struct entry *v = NULL;
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
        struct entry *g = realloc(v, (size_t)(n + 1) * sizeof *v);
        if (!g)
            break;
        v = g;
        struct entry *x = &v[n++];
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
    }
    closedir(d);
    if (n > 1)
        qsort(v, (size_t)n, sizeof *v, by_when);
    *out = v;
    return n;
}

/* Everything one status call shows. */
struct view {
    const struct queue_waiting *w;
    const struct entry *r, *dn, *f;
    int nw, nr, nd, nf, ns;
    const struct queue_studies_entry *studies;
};

/* Elapsed seconds of a running entry (since its claim) and its ETA (-1: unknown). */
static void running_times(const struct entry *x, double *elapsed, double *eta)
{
    *elapsed = x->age_s >= 0 && x->lease.start > 0 && time(NULL) >= x->lease.start
                   ? (double)(time(NULL) - x->lease.start)
                   : -1;
    *eta = -1;
    if (x->lease.rows > 0 && x->lease.rows_done > 0)
        *eta = x->lease.render_s * (x->lease.rows - x->lease.rows_done) / x->lease.rows_done;
}

static double percent(const struct entry *x)
{
    return x->lease.rows > 0 ? 100.0 * x->lease.rows_done / x->lease.rows : 0;
}

static void print_text(const char *dir, const struct view *v)
{
    char when[64];
    const struct queue_waiting *w = v->w;
    const struct entry *r = v->r, *dn = v->dn, *f = v->f;
    int nw = v->nw, nr = v->nr, nd = v->nd, nf = v->nf;
    printf("queue %s: %d waiting, %d running, %d done, %d failed", dir, nw, nr, nd, nf);
    if (v->ns)
        printf(", %d stud%s spread over it", v->ns, v->ns == 1 ? "y" : "ies");
    printf("\n");
    if (nw)
        printf("waiting (in claim order):\n");
    for (int i = 0; i < nw; i++) {
        iso8601(w[i].mtime.tv_sec, when, sizeof when);
        printf("  %3d. %s  priority %d  queued %s\n", i + 1, w[i].name, w[i].priority, when);
    }
    if (nr)
        printf("running:\n");
    for (int i = 0; i < nr; i++) {
        double elapsed, eta;
        running_times(&r[i], &elapsed, &eta);
        if (r[i].age_s < 0) {
            printf("  %s  (no lease yet)\n", r[i].file);
            continue;
        }
        char eta_s[32] = "--", elapsed_s[32] = "--";
        if (eta >= 0)
            snprintf(eta_s, sizeof eta_s, "%.0f s", eta);
        if (elapsed >= 0)
            snprintf(elapsed_s, sizeof elapsed_s, "%.0f s", elapsed);
        printf("  %s  host %s  pid %ld  attempt %d  %.0f%% (%d/%d rows)  elapsed %s  ETA %s\n", r[i].file,
               r[i].lease.host, r[i].lease.pid, r[i].lease.attempt, percent(&r[i]), r[i].lease.rows_done,
               r[i].lease.rows, elapsed_s, eta_s);
    }
    queue_studies_print(v->studies, v->ns);
    if (nd)
        printf("done:\n");
    for (int i = 0; i < nd; i++) {
        iso8601(dn[i].when.tv_sec, when, sizeof when);
        if (dn[i].wall_s < 0)
            printf("  %s  finished %s  (no sidecar)\n", dn[i].file, when);
        else if (dn[i].images > 1) /* a compare job: its images' figures summed */
            printf("  %s  finished %s  %d images  wall (sum) %.2f s  cpu %.2f s  samples %.0f\n", dn[i].file,
                   when, dn[i].images, dn[i].wall_s, dn[i].cpu_s, dn[i].samples);
        else
            printf("  %s  finished %s  wall %.2f s  cpu %.2f s  samples %.0f\n", dn[i].file, when,
                   dn[i].wall_s, dn[i].cpu_s, dn[i].samples);
    }
    if (nf)
        printf("failed:\n");
    for (int i = 0; i < nf; i++)
        printf("  %s  %s\n", f[i].file, f[i].reason);
}

static void json_maybe(struct json *js, const char *key, double v)
{
    json_number(js, key, v < 0 ? (double)NAN : v); /* non-finite: null (unknown) */
}

static void print_json(const char *dir, const struct view *v)
{
    struct json js;
    char when[64];
    const struct queue_waiting *w = v->w;
    const struct entry *r = v->r, *dn = v->dn, *f = v->f;
    int nw = v->nw, nr = v->nr, nd = v->nd, nf = v->nf;
    json_init(&js);
    json_begin_object(&js, NULL);
    json_string(&js, "queue", dir);
    json_begin_array(&js, "waiting");
    for (int i = 0; i < nw; i++) {
        json_begin_object(&js, NULL);
        json_string(&js, "file", w[i].name);
        json_number(&js, "priority", w[i].priority);
        iso8601(w[i].mtime.tv_sec, when, sizeof when);
        json_string(&js, "queued", when);
        json_end_object(&js);
    }
    json_end_array(&js);
    json_begin_array(&js, "running");
    for (int i = 0; i < nr; i++) {
        double elapsed, eta;
        running_times(&r[i], &elapsed, &eta);
        json_begin_object(&js, NULL);
        json_string(&js, "file", r[i].file);
        json_string(&js, "name", r[i].name);
        json_string(&js, "host", r[i].lease.host);
        json_number(&js, "pid", (double)r[i].lease.pid);
        json_number(&js, "attempt", r[i].lease.attempt);
        json_number(&js, "processes", r[i].lease.processes);
        json_number(&js, "rows_done", r[i].lease.rows_done);
        json_number(&js, "rows", r[i].lease.rows);
        json_number(&js, "percent", percent(&r[i]));
        json_maybe(&js, "elapsed_s", elapsed);
        json_maybe(&js, "eta_s", eta);
        json_maybe(&js, "lease_age_s", r[i].age_s);
        json_end_object(&js);
    }
    json_end_array(&js);
    queue_studies_json(&js, v->studies, v->ns);
    json_begin_array(&js, "done");
    for (int i = 0; i < nd; i++) {
        json_begin_object(&js, NULL);
        json_string(&js, "file", dn[i].file);
        json_string(&js, "name", dn[i].name);
        iso8601(dn[i].when.tv_sec, when, sizeof when);
        json_string(&js, "finished", when);
        json_maybe(&js, "wall_s", dn[i].wall_s);
        json_maybe(&js, "cpu_s", dn[i].cpu_s);
        json_maybe(&js, "samples", dn[i].samples);
        json_number(&js, "images", dn[i].images);
        json_end_object(&js);
    }
    json_end_array(&js);
    json_begin_array(&js, "failed");
    for (int i = 0; i < nf; i++) {
        json_begin_object(&js, NULL);
        json_string(&js, "file", f[i].file);
        json_string(&js, "name", f[i].name);
        iso8601(f[i].when.tv_sec, when, sizeof when);
        json_string(&js, "failed", when);
        json_string(&js, "reason", f[i].reason);
        json_end_object(&js);
    }
    json_end_array(&js);
    json_end_object(&js);
    if (!js.oom)
        printf("%.*s\n", (int)js.len, js.buf);
    json_free(&js);
}

int queue_status_dir(const char *cmd, const char *arg, char *out, size_t n)
{
    struct stat st;
    snprintf(out, n, "%s", arg);
    for (size_t l = strlen(out); l > 1 && out[l - 1] == '/'; l--)
        out[l - 1] = 0;
    int bad = stat(out, &st) < 0 ? errno : S_ISDIR(st.st_mode) ? 0 : ENOTDIR;
    if (bad)
        err_print("worker %s: %s: %s\n", cmd, out, strerror(bad));
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
    if (queue_status_dir("status", dir_arg, dir, sizeof dir))
        return 2;
    struct queue_scan scan = {0};
    struct queue_waiting *w = NULL;
    struct entry *r = NULL, *dn = NULL, *f = NULL;
    struct queue_studies_entry *studies = NULL;
    int nw = queue_scan_waiting(&scan, dir, &w), rc = 0;
    char done[1100];
    snprintf(done, sizeof done, "%s/done", dir);
    snprintf(sub, sizeof sub, "%s/running", dir);
    const char *bad = nw < 0 && errno != ENOENT ? "." : NULL;
    int bad_errno = errno;
    int nr = list_folder(sub, "running", done, &r);
    if (nr < 0)
        bad = "running", bad_errno = errno;
    int nd = list_folder(done, "done", done, &dn);
    if (nd < 0)
        bad = "done", bad_errno = errno;
    snprintf(sub, sizeof sub, "%s/failed", dir);
    int nf = list_folder(sub, "failed", done, &f);
    if (nf < 0)
        bad = "failed", bad_errno = errno;
    int ns = queue_studies_list(dir, &studies);
    if (ns < 0)
        bad = QUEUE_STUDY_DIR, bad_errno = errno;
    if (bad) { /* a folder that cannot be read is no empty one: "0 failed" would be a lie */
        err_print("worker status: %s/%s: cannot be read: %s\n", dir, bad, strerror(bad_errno));
        rc = 2;
    } else {
        struct view v = {w, r, dn, f, nw < 0 ? 0 : nw, nr, nd, nf, ns < 0 ? 0 : ns, studies};
        if (json)
            print_json(dir, &v);
        else
            print_text(dir, &v);
    }
    free(w);
    free(r);
    free(dn);
    free(f);
    free(studies);
    queue_scan_free(&scan);
    return rc;
}
