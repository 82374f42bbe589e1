/* queue_status: `worker status DIR`, a queue seen by people (SPEC "Additions"): it reads the
   queue's files and never takes a claim, so it runs beside live workers. */
#ifndef QUEUE_STATUS_H
#define QUEUE_STATUS_H

#include <stddef.h>

/* worker status DIR [--json], with argv[0] = "status": waiting jobs in claim order (priority,
   age), running ones with host, pid, attempt, percent of rows, elapsed and ETA from their lease,
   done ones with finish time, wall and CPU seconds and samples from their sidecar, failed ones
   with their log's reason. Text on stdout, or one JSON object. Exit 0, or 2 (bad usage, no
   queue: one line on stderr). */
int queue_status_main(int argc, char **argv);

/* The job name of the job file at path (file: its name in its folder): its `name:` when it has a
   valid-looking one, else the file's stem. */
void queue_status_job_name(const char *path, const char *file, char *out, size_t n);

/* DIR (arg) without trailing slashes into out; 0, or 2 after one line ("<who>DIR: reason", who
   such as "worker status: ") when it is no directory. */
int queue_status_dir(const char *who, const char *arg, char *out, size_t n);

#endif
