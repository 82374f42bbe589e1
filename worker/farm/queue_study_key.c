/* queue_study_key: a study folder's record of what was written into it, and its check. */
#include "queue_study_key.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/fileio.h"
#include "base/hash.h"
#include "queue_scan.h"
#include "queue_types.h"

/* Most bytes study.key may hold (an entry line is under 32 bytes; a study has at most a few
   hundred thousand entries). */
#define KEY_MAX_BYTES (16u << 20)

void queue_study_key_begin(struct sbuf *b, const uint8_t *job, size_t len)
{
    sbuf_printf(b, "worker study key 1\njob %016llx\n",
                (unsigned long long)hash_bytes(HASH_FNV_OFFSET, job, len));
}

void queue_study_key_add(struct sbuf *b, const char *entry)
{
    sbuf_printf(b, "entry %s\n", entry);
}

/* Read the regular file path (never through a link, never blocking) of at most max bytes into a
   malloc'd NUL-terminated buffer. 0, or -1. */
static int read_plain(const char *path, size_t max, char **text, size_t *len)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    struct stat st;
    *text = NULL;
    if (fd < 0)
        return -1;
    if (fstat(fd, &st) < 0 || !S_ISREG(st.st_mode) || (size_t)st.st_size > max ||
        !(*text = malloc((size_t)st.st_size + 1))) {
        close(fd);
        return -1;
    }
    size_t got = 0;
    ssize_t r = 1;
    while (got < (size_t)st.st_size && (r = read(fd, *text + got, (size_t)st.st_size - got)) > 0)
        got += (size_t)r;
    close(fd);
    if (r < 0 || got != (size_t)st.st_size) {
        free(*text);
        *text = NULL;
        return -1;
    }
    (*text)[got] = 0;
    *len = got;
    return 0;
}

int queue_study_key_same(const char *path, uint64_t h)
{
    char *text;
    size_t len;
    if (read_plain(path, KEY_MAX_BYTES, &text, &len) < 0)
        return 0;
    int same = hash_bytes(HASH_FNV_OFFSET, text, len) == h;
    free(text);
    return same;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(a, b);
}

/* Load sd/study.key into k. 0, or -1 with why. */
static int load(const char *sd, struct study_key *k, char *why, size_t n)
{
    char path[2300], *text, *line, *next;
    size_t len;
    unsigned long long h;
    memset(k, 0, sizeof *k);
    snprintf(path, sizeof path, "%s/study.key", sd);
    if (read_plain(path, KEY_MAX_BYTES, &text, &len) < 0) {
        snprintf(why, n, "%s: %s, not the record this worker writes (a regular file)", path,
                 fileio_kind(path) ? fileio_kind(path) : "missing");
        return -1;
    }
    int ok = sscanf(text, "worker study key 1\njob %16llx\n", &h) == 1;
    int lines = 0;
    for (line = text; ok && *line; line = next, lines++) {
        next = strchr(line, '\n');
        ok = next != NULL;
        if (!ok)
            break;
        *next++ = 0;
        if (lines < 2 || strncmp(line, "entry ", 6))
            continue;
        ok = strlen(line + 6) < sizeof k->entry[0] && queue_scan_is_job_file(line + 6);
        if (ok && (k->n & (k->n - 1)) == 0) { /* grown at each power of two: linear in the entries */
            char(*g)[32] = realloc(k->entry, (size_t)(k->n ? 2 * k->n : 1) * sizeof *g);
            ok = g != NULL;
            if (g)
                k->entry = g;
        }
        if (ok)
            snprintf(k->entry[k->n++], sizeof k->entry[0], "%s", line + 6);
    }
    free(text);
    if (!ok) {
        snprintf(why, n, "%s: not the record this worker wrote (damaged or forged)", path);
        return -1;
    }
    k->job_hash = h;
    if (k->n > 1)
        qsort(k->entry, (size_t)k->n, sizeof k->entry[0], by_name);
    return 0;
}

int queue_study_key_has(const struct study_key *k, const char *entry)
{
    return strlen(entry) < sizeof k->entry[0] && k->n &&
           bsearch(entry, k->entry, (size_t)k->n, sizeof k->entry[0], by_name) != NULL;
}

void queue_study_key_free(struct study_key *k)
{
    free(k->entry);
    memset(k, 0, sizeof *k);
}

/* Why the folder sd/sub is not a real folder (a link, a file, missing): into why; 0 when it is one. */
static int not_folder(const char *sd, const char *sub, char *why, size_t n)
{
    char path[2300];
    struct stat st;
    snprintf(path, sizeof path, "%s/%s", sd, sub);
    if (lstat(path, &st) == 0 && S_ISDIR(st.st_mode))
        return 0;
    snprintf(why, n, "%s is %s, not a folder of the study's", path,
             fileio_kind(path) ? fileio_kind(path) : "missing");
    return 1;
}

enum queue_study_state queue_study_state(const char *dir, const char *sd, const char *stem,
                                         struct study_key *k, int hash_jobs, char *why, size_t n)
{
    char path[2300];
    struct stat st;
    const char *subs[] = {"job", "running", "done", "failed"};
    memset(k, 0, sizeof *k);
    for (int i = 0; i < 4; i++)
        if (not_folder(sd, subs[i], why, n))
            return QUEUE_STUDY_DAMAGED;
    int gather_filed = queue_scan_has(sd, "done/" QUEUE_STUDY_GATHER);
    snprintf(path, sizeof path, "%s/job/%s.yaml", sd, stem);
    int job_filed = lstat(path, &st) == 0;
    if (gather_filed && !job_filed) /* the record of a finished study: nothing more is read */
        return QUEUE_STUDY_FINISHED;
    if (load(sd, k, why, n) < 0)
        return QUEUE_STUDY_DAMAGED;
    snprintf(path, sizeof path, "%s/study.job", sd);
    int regular = lstat(path, &st) == 0 && S_ISREG(st.st_mode);
    if (!regular || (hash_jobs && !queue_study_key_same(path, k->job_hash))) {
        if (regular)
            snprintf(why, n, "%s: not the job that was spread (its hash is not the one study.key records)",
                     path);
        else
            snprintf(why, n, "%s: %s, not the job file the study was spread from", path,
                     fileio_kind(path) ? fileio_kind(path) : "missing");
        return QUEUE_STUDY_DAMAGED;
    }
    snprintf(path, sizeof path, "%s/job/%s.yaml", sd, stem);
    if (job_filed && lstat(path, &st) == 0) {
        /* a job file queued as a symbolic link is filed as that link: its target is the user's */
        if (hash_jobs && !S_ISLNK(st.st_mode) && !queue_study_key_same(path, k->job_hash)) {
            snprintf(why, n,
                     "%s: changed since the study was spread (its hash is not the one study.key records)",
                     path);
            return QUEUE_STUDY_DAMAGED;
        }
        if (gather_filed) {
            snprintf(why, n,
                     "%s/done/%s: filed as done, but the study was never gathered (its job file is "
                     "still in job/)",
                     sd, QUEUE_STUDY_GATHER);
            return QUEUE_STUDY_DAMAGED;
        }
        return QUEUE_STUDY_ACTIVE;
    }
    snprintf(path, sizeof path, "%s/done/%s.yaml", dir, stem);
    int linked = lstat(path, &st) == 0 && S_ISLNK(st.st_mode); /* a job queued as a link, filed as one */
    return linked || queue_study_key_same(path, k->job_hash) ? QUEUE_STUDY_GATHERED : QUEUE_STUDY_SPREADING;
}
