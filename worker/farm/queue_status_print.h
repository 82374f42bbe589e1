/* queue_status_print: `worker status`'s two printers, text and JSON, of what queue_status.c read
   from a queue's folders. */
#ifndef QUEUE_STATUS_PRINT_H
#define QUEUE_STATUS_PRINT_H

#include <time.h>

#include "lease.h"
#include "queue_scan.h"
#include "queue_studies.h"

/* One job file of done/ or failed/ (or running/), with what status says about it. */
struct status_entry {
    char file[256];
    char name[256]; /* the job's name: its `name:`, else the file's stem */
    struct timespec when;
    double wall_s, cpu_s, samples; /* done: from the sidecar (a compare job's: summed); < 0 unknown */
    int images;                    /* done: sidecars summed */
    char reason[512];              /* failed: the log's error, first line */
    struct lease lease;            /* running */
    double age_s;                  /* running: seconds since the lease was renewed; < 0 no lease */
    int gone;                      /* running: its worker is known to be dead (same host, no pid) */
};

/* Everything one status call shows. */
struct status_view {
    const struct queue_waiting *w;
    const struct status_entry *r, *dn, *f;
    int nw, nr, nd, nf, ns;
    const struct queue_studies_entry *studies;
};

/* The view of queue dir as text (a line per job under waiting, running, done, failed) or as one
   JSON object, on stdout. */
void queue_status_print_text(const char *dir, const struct status_view *v);
void queue_status_print_json(const char *dir, const struct status_view *v);

#endif
