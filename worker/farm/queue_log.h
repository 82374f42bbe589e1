/* queue_log: the lines a queue worker writes on stderr, each with an ISO 8601 time and the job file
   it is about, and the warning that one host's workers run more render processes than it has
   cores. */
#ifndef QUEUE_LOG_H
#define QUEUE_LOG_H

#include <time.h>

#include "lease.h"

/* t as the log's time, ISO 8601 in UTC ("2025-06-01T10:02:11Z"), into out (n bytes); returns out. */
char *queue_log_time(time_t t, char *out, size_t n);

/* One line on stderr: "2025-06-01T10:02:11Z x.yaml: message" (UTC; file is the job file's name in
   the queue; a trailing newline in fmt is dropped). */
void queue_log(const char *file, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Warn (queue_log) when this claim's `processes` and the other claims' on this host together
   exceed its cores: renders that share cores slow each other down. */
void queue_log_check_cores(const char *running, const struct lease *me, const char *claim, const char *file,
                           int processes);

#endif
