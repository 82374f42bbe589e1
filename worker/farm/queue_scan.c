/* queue_scan: the waiting jobs of a queue directory in claim order, with their priorities. */
#include "queue_scan.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "base/clock.h"
#include "base/fileio.h"
#include "scenefile/yamlx.h"

int queue_scan_is_job_file(const char *s)
{
    size_t n = strlen(s);
    return s[0] != '.' && n > 5 && strcmp(s + n - 5, ".yaml") == 0;
}

int queue_scan_has(const char *dir, const char *name)
{
    char path[2600];
    struct stat st;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return lstat(path, &st) == 0;
}

/* A waiting job's priority: its `priority:` key, 0 when absent or unreadable (loading the job
   later reports the error). */
static int peek_priority(const char *path)
{
    struct ydoc d;
    struct err e;
    uint8_t *text;
    size_t len;
    int p = 0;
    if (fileio_read_all(path, YDOC_MAX_BYTES, &text, &len, &e) < 0)
        return 0;
    /* most jobs: no YAML parse on every scan; the rest parsed from the bytes read */
    if (strstr((const char *)text, "priority") && ydoc_parse(&d, path, text, len, &e) == 0) {
        yaml_node_t *root = ydoc_root(&d);
        yaml_node_t *v = root && root->type == YAML_MAPPING_NODE ? ymap_get(&d, root, "priority") : NULL;
        const char *s = v ? yscalar(v) : NULL;
        if (s) {
            char *end;
            long n = strtol(s, &end, 10);
            if (*s && !*end && n >= -1000000 && n <= 1000000)
                p = (int)n;
        }
        ydoc_free(&d);
    }
    free(text);
    return p;
}

/* An empty file changed less than QUEUE_SCAN_EMPTY_GRACE_S ago: a copier (cp, scp) has created it
   and not yet written it (a small job file is written in one go). Left for a later scan; an older
   empty file is claimed and filed in failed/ as invalid. Files with content are claimed at once. */
static int just_created(const struct stat *st)
{
    double age = clock_s(CLOCK_REALTIME) - (st->st_mtim.tv_sec + st->st_mtim.tv_nsec * 1e-9);
    return st->st_size == 0 && age < QUEUE_SCAN_EMPTY_GRACE_S;
}

/* Higher priority first, then oldest (mtime), then by name. */
static int waiting_cmp(const void *pa, const void *pb)
{
    const struct queue_waiting *a = pa, *b = pb;
    if (a->priority != b->priority)
        return a->priority > b->priority ? -1 : 1;
    if (a->mtime.tv_sec != b->mtime.tv_sec)
        return a->mtime.tv_sec < b->mtime.tv_sec ? -1 : 1;
    if (a->mtime.tv_nsec != b->mtime.tv_nsec)
        return a->mtime.tv_nsec < b->mtime.tv_nsec ? -1 : 1;
    return strcmp(a->name, b->name);
}

static int by_name(const void *pa, const void *pb)
{
    return strcmp(((const struct queue_waiting *)pa)->name, ((const struct queue_waiting *)pb)->name);
}

/* The priority of the waiting job w (name and stat filled) at path: the last scan's when the file is
   unchanged (same inode, size and mtime), else read from the file. Reading every waiting file on
   every scan cost a queue of N jobs N*N/2 reads (on NFS, several round trips each). */
static int priority_of(const struct queue_scan *q, const struct queue_waiting *w, const char *path)
{
    const struct queue_waiting *old =
        q->nseen ? bsearch(w, q->seen, (size_t)q->nseen, sizeof *w, by_name) : NULL;
    if (old && old->ino == w->ino && old->size == w->size && old->mtime.tv_sec == w->mtime.tv_sec &&
        old->mtime.tv_nsec == w->mtime.tv_nsec)
        return old->priority;
    return peek_priority(path);
}

/* Keep a copy of this scan's n jobs w, sorted by name, for the next scan's priority_of. */
static void remember(struct queue_scan *q, const struct queue_waiting *w, int n)
{
    struct queue_waiting *c = n > 0 ? malloc((size_t)n * sizeof *c) : NULL;
    free(q->seen);
    q->seen = c;
    q->nseen = c ? n : 0;
    if (!c)
        return;
    memcpy(c, w, (size_t)n * sizeof *c);
    qsort(c, (size_t)n, sizeof *c, by_name);
}

static void note_unrunnable(struct queue_scan *q, const char *name)
{
    char(*g)[256] = realloc(q->unrunnable, (size_t)(q->nunrunnable + 1) * sizeof *g);
    if (!g)
        return;
    q->unrunnable = g;
    snprintf(g[q->nunrunnable++], sizeof *g, "%s", name);
}

int queue_scan_waiting(struct queue_scan *q, const char *dir, struct queue_waiting **out)
{
    DIR *d = opendir(dir);
    *out = NULL;
    q->nunrunnable = 0;
    if (!d)
        return -1;
    struct queue_waiting *w = NULL;
    int n = 0, cap = 0;
    struct dirent *de;
    while ((de = readdir(d))) {
        char path[2048];
        struct stat st;
        if (!queue_scan_is_job_file(de->d_name) || strlen(de->d_name) >= sizeof w->name)
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        int bad = stat(path, &st) < 0 ? errno : 0;
        if (bad && bad != ELOOP && (lstat(path, &st) < 0 || !S_ISLNK(st.st_mode)))
            continue;                      /* claimed meanwhile */
        if (bad || !S_ISREG(st.st_mode)) { /* a dangling or looping link, a FIFO, a folder */
            note_unrunnable(q, de->d_name);
            continue;
        }
        if (just_created(&st))
            continue;
        if (n == cap) {
            cap = cap ? cap * 2 : 64;
            struct queue_waiting *g = realloc(w, (size_t)cap * sizeof *w);
            if (!g)
                break;
            w = g;
        }
        snprintf(w[n].name, sizeof w[n].name, "%s", de->d_name);
        w[n].mtime = st.st_mtim;
        w[n].ino = st.st_ino;
        w[n].size = st.st_size;
        w[n].priority = priority_of(q, &w[n], path);
        n++;
    }
    closedir(d);
    remember(q, w, n);
    if (n > 1)
        qsort(w, (size_t)n, sizeof *w, waiting_cmp);
    *out = w;
    return n;
}

void queue_scan_free(struct queue_scan *q)
{
    free(q->seen);
    q->seen = NULL;
    q->nseen = 0;
    free(q->unrunnable);
    q->unrunnable = NULL;
    q->nunrunnable = 0;
}
