/* queue_types: a queue's options and the names of its folders, types only, for every queue
   module that needs them without the module that drives the queue (queue.h) or spreads a
   study (queue_study.h). */
#ifndef QUEUE_TYPES_H
#define QUEUE_TYPES_H

#include "job/run.h"

/* Layout under DIR: waiting jobs DIR/X.yaml; claims DIR/running/X.yaml with their lease
   DIR/running/X.yaml.lease ("host H", "pid P", "start S", "token T", "pids B:N" lines, mtime refreshed while
   rendering); finished DIR/done/X.yaml with outputs in DIR/done/<name>/; failed DIR/failed/X.yaml
   and DIR/failed/<name>.log. */
struct queue_opts {
    const char *dir;
    int once;               /* exit when no job is waiting */
    double poll_s;          /* seconds between scans of an empty queue */
    int retries;            /* renders of a job whose render process crashed, after the first */
    double lease_timeout_s; /* a lease not refreshed for this long is dead, whatever its host */
    double entry_cpu_s;     /* a study's entries' CPU target (spread_plan.h) unless its job gives one */
    const char *entry;      /* --entry NAME: render that entry of the one study given (no queue) */
    struct run_opts run;    /* processes, quiet, progress, force; out_dir is set to DIR/done */
};

/* The folder below DIR that holds the studies in progress. */
#define QUEUE_STUDY_DIR "spread"

/* The three kinds of entry, named so that claim order is their order: a-ref-K-S.yaml (study K's
   reference of scene S), b-img-K-I.yaml (its image I), c-gather.yaml. */
#define QUEUE_STUDY_GATHER "c-gather.yaml"

#endif
