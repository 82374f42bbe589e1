/* queue_claim: a queue worker's claims: take a waiting job into running/ by rename() with our
   lease, renew the lease while rendering, file the claim as done or failed, and recover dead
   workers' claims (returned to the queue, or taken over in place). Owns struct queue, the state
   of one worker draining a queue directory. */
#ifndef QUEUE_CLAIM_H
#define QUEUE_CLAIM_H

#include <signal.h>
#include <stddef.h>
#include <time.h>

#include "lease.h"
#include "queue_scan.h"
#include "queue_types.h"

struct queue {
    const struct queue_opts *o;
    char dir[1024], running[1100], done[1100], failed[1100];
    struct lease lease; /* ours, for the claim in hand */
    char claim[2048];   /* DIR/running/X.yaml while a job is held */
    double last_touch;  /* CLOCK_MONOTONIC seconds (clock_s) of the lease's last renewal */
    int worst;
    int took;                    /* claims processed (a --once worker that took none says so) */
    int filed;                   /* unrunnable entries this worker moved to failed/ */
    char as_name[256];           /* the job file name whose outputs the claims may write ("": the claim's own;
                                    a study's render entries: the study's job file) */
    struct queue_scan scan;      /* the waiting jobs seen by the last scan */
    volatile sig_atomic_t *stop; /* the queue's stop flag, which also stops the render in hand */
    int lost;                    /* the claim in hand was found gone or taken over (tick) */
    int attempt;                 /* the render attempt of the claim in hand (1, 2 after a crash) */
    int processes;               /* its render processes (0 until its job is loaded) */
    char name_owner[2048];       /* its output folder holds another queued job file's outputs */
    char name_dir[2048];         /* that folder */
    char spreading[256];         /* the compare job being spread elsewhere that a --once worker waits for */
    char waits_requeue[256];     /* a study whose remaining work waits for its failed renders' requeue */
    char reported[64][256];      /* unrunnable entries said once already (they could not be moved) */
    int nreported;
    int env_failed;     /* a job's output folder could not be written (outdir_env_error): stop, exit 2 */
    struct err env_err; /* a study entry's such error (queue_drain), for the log */
};

/* *queue.stop's value when the tick found the claim in hand gone (not a signal number): the render
   stops, writes nothing, and the worker goes on with the next job. */
#define QUEUE_STOP_CLAIM_LOST (-1)

/* Begin processing the claim in hand: its per-claim state reset, and its lease renewed from a timer
   (SIGALRM) whatever the worker is doing (loading a scene, encoding an image, waiting for a lock): the
   tick runs only while render processes run. A stopped or dead worker renews nothing; the lease file
   is held open, so a lease rewritten by a new holder is not touched. */
void queue_claim_begin(struct queue *q);

/* End it: the timer stopped, and the tick's "claim lost" stop over (*q->stop is the queue's again;
   a signal that came meanwhile is kept). */
void queue_claim_end(struct queue *q);

/* Move the claim at `claim` (file `name`) back to DIR under its recovery lock; the lease goes first
   so that nobody can mistake a fresh claim's lease for the old one. 0 when moved. */
int queue_claim_return(struct queue *q, const char *claim, const char *name);

/* Return every dead worker's claim to the queue. A dead claim whose file name waits in DIR again
   is taken over in place instead (its name into `adopted`, and 1: process it now), so that both
   jobs are rendered, this one first. */
int queue_claim_recover(struct queue *q, char *adopted, size_t n);

/* Claim DIR/name into running/ and write our lease. 0 when the job is ours; 1 when another worker
   was first, or a job of its file name is running; -1 when the queue cannot be written (said on
   stderr: a read-only DIR, no permission, a full disk). */
int queue_claim_take(struct queue *q, const char *name);

/* The file to read the job claimed at `claim` (DIR/running/X.yaml) from: the claim itself, or, when
   the job was a symbolic link with a relative target, that target seen from DIR, where the link was
   made (the claim moved the link into running/, where its target would be looked up beside
   running/). */
void queue_claim_source(const struct queue *q, const char *claim, char *out, size_t n);

/* Still ours? The claim's file is still in running/ (not removed or moved away) and nobody took
   the claim away while we rendered (a lease judged dead elsewhere). */
int queue_claim_still_ours(struct queue *q);

/* The run options of a render of the claim in hand: the worker's --run options, outputs into
   DIR/done, q's stop flag, and the claim's tick, may_write and still_held on held (q itself, or
   the study queue whose render entry is held). */
struct run_opts queue_claim_run_opts(const struct queue *q, struct queue *held);

/* The job file (its file name) whose outputs output folder `dir` holds, when that is not the claim
   in hand's file name: its path (a sidecar's "job_file") into owner, and 1. 0 when the folder is
   empty, absent or the claim's own (the same file re-queued, edited or not). */
int queue_claim_name_owner(const struct queue *q, const char *dir, char *owner, size_t n);

/* Take the claim in hand's recovery lock (lease_lock), trying for about a second. 0 when taken. */
int queue_claim_lock(struct queue *q);

/* Move the claim to done/ or failed/ and drop the lease: the lease first, under the recovery
   lock, so that a re-queued file of the same name claimed the next instant keeps its own. */
void queue_claim_file(struct queue *q, const char *name, const char *to_dir);

#endif
