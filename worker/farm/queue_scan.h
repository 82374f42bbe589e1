/* queue_scan: the waiting jobs of a queue directory (the files DIR/X.yaml) in claim order: higher
   `priority:` first, then oldest (mtime), then by name. */
#ifndef QUEUE_SCAN_H
#define QUEUE_SCAN_H

#include <sys/types.h>
#include <time.h>

struct queue_waiting {
    char name[256];
    int priority;
    struct timespec mtime;
    ino_t ino;
    off_t size;
};

/* What one scan leaves for the next: the jobs it saw, by name, so that the priority of a file
   that has not changed (inode, size, mtime) is not read again. Zero-initialise; free with
   queue_scan_free. */
struct queue_scan {
    struct queue_waiting *seen;
    int nseen;
    char (*unrunnable)[256]; /* this scan's DIR/X.yaml entries that can never run (see below) */
    int nunrunnable;
};

/* Seconds an empty DIR/X.yaml is left alone after its last change (a copier is about to write it). */
#define QUEUE_SCAN_EMPTY_GRACE_S 10.0

/* 1 when a directory entry's name is a job file's: X.yaml, not hidden (temporaries start with a dot). */
int queue_scan_is_job_file(const char *name);

/* 1 when dir/name exists (as any kind of entry, a link not followed). */
int queue_scan_has(const char *dir, const char *name);

/* The regular files DIR/X.yaml in claim order into *out (malloc'd, the caller frees it); their
   count, or -1 when dir cannot be read (errno says why). The entries named X.yaml that can never
   run (a FIFO, a directory, a socket, a dangling or looping symbolic link) go to s->unrunnable. */
int queue_scan_waiting(struct queue_scan *s, const char *dir, struct queue_waiting **out);

void queue_scan_free(struct queue_scan *s);

#endif
