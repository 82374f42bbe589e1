/* queue_file: filing a queue claim that ends: in failed/ with its log, back to the queue on a stop
   signal, or left to whoever took it over; shared by a worker's jobs and a study's renders. */
#ifndef QUEUE_FILE_H
#define QUEUE_FILE_H

#include "queue_claim.h"

/* failed/<job_name>.log: what went wrong (error), the signal (0: none), the attempts. */
void queue_file_log(struct queue *q, const char *name, const char *job_name, const char *error, int sig,
                    int attempts);

/* The claim in hand (file `name`) given back to the queue after a stop signal ("stopped by signal
   N"): under its recovery lock, and only while it is still ours. One log line. */
void queue_file_stopped(struct queue *q, const char *name);

/* The claim in hand could not be written for a reason of this machine (outdir_env_error(e)): handed
   back with one line saying why, q->env_failed set (the worker stops) and exit status 2 noted. Never
   failed/: one misconfigured worker must not empty the queue. */
void queue_file_env_stop(struct queue *q, const char *name, const struct err *e);

/* The claim in hand is no longer ours and its render wrote nothing: one log line. Its file gone from
   running/ with our lease still beside it is a user's cancel (rm or mv): our lease goes too; else
   another worker took it over (a recovery removes our lease first). */
void queue_file_say_lost(struct queue *q, const char *name);

/* File the claim in hand in failed/, removing first the temporaries a killed writer of an earlier
   attempt left in its output folder done/<job_name>/ (nothing else would). */
void queue_file_failed(struct queue *q, const char *name, const char *job_name);

/* The waiting entry q->dir/name that can never be claimed (not a regular file, or no entry of a
   study), msg saying why: moved to failed/ with its log and one line (label names it), exit status 2
   noted. 0 when moved, -1 with errno when not (ENOENT: another worker filed it). */
int queue_file_aside(struct queue *q, const char *name, const char *label, const char *msg);

/* The claim in hand (file `name`) can never run, msg saying why: msg and "<what>, moved to failed/"
   logged, failed/<log_name>.log written, the claim filed in failed/ (clean: after removing the
   temporaries in done/<log_name>/, as queue_file_failed), exit status 2 noted. */
void queue_file_invalid(struct queue *q, const char *name, const char *log_name, const char *msg,
                        const char *what, int clean);

/* Keep the worst exit status seen (q->worst). */
void queue_file_note_rc(struct queue *q, int rc);

#endif
