/* queue: drain a queue directory of job files with many workers (claims, leases, done/ and failed/). */
#ifndef QUEUE_H
#define QUEUE_H

#include <signal.h>

#include "queue_types.h"

#define QUEUE_POLL_S 2.0
#define QUEUE_RETRIES 1
#define QUEUE_LEASE_TIMEOUT_S 60.0

/* Route SIGINT and SIGTERM to a stop flag: the running render is stopped and its job returned to
   the queue. A second signal terminates the process at once. */
void queue_signals_install(void);

/* Claim, render and file jobs until the queue is empty (once) or a stop signal arrives, returning
   stale claims of dead workers to the queue on every scan. Prints one line per job on stderr.
   Returns the exit status: 0 every job taken was done (or skipped as current, or returned on a
   stop), 1 one failed while rendering, 2 the queue directory is unusable, a job was invalid, or an
   output folder could not be written (outdir_env_error: the claim handed back, the worker stopped). */
int queue_main(const struct queue_opts *qo);

#endif
