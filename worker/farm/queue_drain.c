/* queue_drain: a queue worker's part in the studies spread over its queue: check each study's folder,
   take one of its entries in order (queue_entry processes it), or end a damaged study. */
#include "queue_drain.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/fileio.h"
#include "lease.h"
#include "queue_entry.h"
#include "queue_file.h"
#include "queue_log.h"
#include "queue_study.h"
#include "queue_study_key.h"

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

/* The study's waiting entries (this scan's w, n of them; the unrunnable in sq->scan) that can never
   be claimed go to its failed/ with a log: what is not a regular file, and what the study never wrote
   (its record k). The others are left in w; their count. */
static int set_aside(struct queue *sq, const char *stem, const struct study_key *k, struct queue_waiting *w,
                     int n)
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
    char adopted[256], damaged[2600] = "";
    int result = 0, blocked = 0;
    if (queue_claim_recover(&sq, adopted, sizeof adopted)) {
        queue_entry_process(q, &sq, sd, stem, k, adopted, damaged, sizeof damaged);
        if (damaged[0])
            file_damaged(q, sd, stem, damaged);
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
            queue_entry_process(q, &sq, sd, stem, k, w[i].name, damaged, sizeof damaged);
            result = 1;
        }
    }
    if (n >= 0)
        free(w);
    queue_scan_free(&sq.scan);
    if (damaged[0])
        file_damaged(q, sd, stem, damaged);
    /* a claim held elsewhere: its worker may die before filing it, and a --once worker that left
       would leave it to nobody; it is taken back once judged dead (pid gone, or --lease-timeout) */
    if (result == 0 && earliest_in(sq.running, k) != '~')
        result = 2;
    if (result == 0 && blocked)
        snprintf(q->waits_requeue, sizeof q->waits_requeue, "%s", stem);
    return result;
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
        switch (queue_study_state(q->dir, sd, de->d_name, &k, 0, why, sizeof why)) {
        case QUEUE_STUDY_ACTIVE:
        case QUEUE_STUDY_GATHERED: /* only its gather entry to file */
            r = work_on(q, sd, de->d_name, &k);
            break;
        case QUEUE_STUDY_DAMAGED:
            file_damaged(q, sd, de->d_name, why);
            break;
        case QUEUE_STUDY_FINISHED: /* the gather's recovery lock, left by a worker killed after filing it */
            snprintf(why, sizeof why, "%s/running", sd);
            lease_sweep_locks(why, QUEUE_STUDY_GATHER ".lock", q->o->lease_timeout_s);
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
