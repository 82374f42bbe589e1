/* queue_status: `worker status DIR` and `worker requeue DIR`, a queue seen and steered by people
   (SPEC "Additions"). They read the queue's files and move job files with rename(); they never
   take a claim, so they run beside live workers. */
#ifndef QUEUE_STATUS_H
#define QUEUE_STATUS_H

/* worker status DIR [--json], with argv[0] = "status": waiting jobs in claim order (priority,
   age), running ones with host, pid, attempt, percent of rows, elapsed and ETA from their lease,
   done ones with finish time, wall and CPU seconds and samples from their sidecar, failed ones
   with their log's reason. Text on stdout, or one JSON object. Exit 0, or 2 (bad usage, no
   queue: one line on stderr). */
int queue_status_main(int argc, char **argv);

/* worker requeue DIR NAME... | --failed, with argv[0] = "requeue": move the job files NAME (X or
   X.yaml) from failed/ (or done/) back to DIR, never over a job waiting or running under that
   name; --failed moves every failed job. One line per job on stderr. Exit 0 every one moved, 2
   bad usage or one could not be moved. */
int queue_requeue_main(int argc, char **argv);

#endif
