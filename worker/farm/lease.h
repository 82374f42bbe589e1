/* lease: who holds a queue claim (host, pid, start, token) and whether that holder is dead. */
#ifndef LEASE_H
#define LEASE_H

#include <stddef.h>
#include <sys/types.h>

#include "base/err.h"

struct lease {
    char host[256];
    long pid;
    long long start; /* seconds since the epoch */
    char token[384]; /* unique per claim: host:pid:start_ns */
    char pids[128];  /* the pid space `pid` lives in: "<boot id>:<pid namespace>" ("" unknown) */
    /* the last line, "progress D R S A P", fixed width so that the holder rewrites it in place:
       rows done of R, seconds the render has run, render attempt, render processes (all 0 until
       it starts; a lease of an earlier version has no P) */
    int rows_done, rows, attempt, processes;
    double render_s;
    int broke; /* a recovery lock's: its holder took it from a holder that was gone (lease_lock) */
};

/* Most bytes a lease file may hold (one is larger: not a lease), and most rows it may count. */
#define LEASE_MAX_BYTES 4096
#define LEASE_MAX_ROWS 32768

/* Bytes of the lease's last line, "progress ...\n" (lease_progress rewrites it). */
#define LEASE_PROGRESS_LEN 56

/* This process's lease for a claim made now (hostname, getpid, the time, a fresh token, and on
   Linux the pid space: the kernel's boot id and the pid namespace, since containers sharing the
   host's name, or cloned machines, share the hostname but not their pids). */
void lease_init(struct lease *l);

/* Write l beside the claim file (claim + ".lease") atomically. 0 or -1 with e filled. */
int lease_write(const char *claim, const struct lease *l, struct err *e);

/* Read the lease of claim into l and its age (seconds since its mtime). 0, or -1 when it is
   missing, unreadable or no regular file of at most LEASE_MAX_BYTES (a FIFO or a link to a device
   is never opened for reading: it would block or never end). Its words are printable ASCII ('?'
   for anything else) and its numbers within a live worker's range (else 0, unknown). */
int lease_read(const char *claim, struct lease *l, double *age_s);

/* Rewrite the progress line of the lease open as fd (O_RDWR, as lease_write wrote it) in place,
   which renews it too (its mtime). Async-signal-safe; failure is ignored (the next call retries). */
void lease_progress(int fd, int rows_done, int rows, double render_s, int attempt, int processes);

/* Refresh the lease's mtime (the holder is alive). Failure is ignored: the next call retries. */
void lease_touch(const char *claim);

/* Remove the lease file of claim. */
void lease_remove(const char *claim);

/* 1 when the claim's holder is dead: on this host (same hostname and, when both leases know it,
   same pid space) its pid is gone; on any host its lease was not
   refreshed for timeout_s; without a lease, the claim's recovery lock names a holder of this host
   that is gone (killed while filing it), or the claim is older than timeout_s (the holder died
   between claiming and writing it). why gets a short reason. 0 when alive, or the claim is gone. */
int lease_stale(const char *claim, double timeout_s, char *why, size_t n);

/* Take the claim's recovery lock (claim + ".lock", created exclusively, naming its holder as a lease
   does) that serialises whoever returns or files the claim. 0 when taken; -1 when another holds it
   (a lock older than timeout_s, or whose holder of this host is gone, is broken so that a death
   cannot block the job for ever, and taken when no other was quicker). */
int lease_lock(const char *claim, double timeout_s);
void lease_unlock(const char *claim);

/* The entry `name` of folder running/ when it is the recovery lock of a claim that is no longer
   there (its holder killed after the claim was filed, before the unlock): removed once its holder
   is gone (this host) or it is older than timeout_s. Anything else is left alone. */
void lease_sweep_locks(const char *running, const char *name, double timeout_s);

#endif
