/* queue_study: a compare job or suite in a queue spread over its workers. The worker that claims
   it writes one render entry per reference and per image into DIR/spread/<stem>/ (a queue of its
   own: running/, done/, failed/, with the same claims, leases, retries and recovery) and files the
   job there (job/<X>.yaml); workers drain those entries, references first; the entry claimed last
   gathers summary.csv, chart, report and verdict into done/<name>/, then files the job file in
   done/ (queue_drain.h). This module makes the study's folder. */
#ifndef QUEUE_STUDY_H
#define QUEUE_STUDY_H

#include "queue_claim.h"

/* The folder below DIR that holds the studies in progress. */
#define QUEUE_STUDY_DIR "spread"

/* The three kinds of entry, named so that claim order is their order: a-ref-K-S.yaml (study K's
   reference of scene S), b-img-K-I.yaml (its image I), c-gather.yaml. */
#define QUEUE_STUDY_GATHER "c-gather.yaml"

/* Spread the claimed compare job DIR/running/name (read from `from`, its paths as at `as`, stem
   its file's stem) over the queue; an invalid one goes to failed/ as any job. */
void queue_study_expand(struct queue *q, const char *name, const char *from, const char *as,
                        const char *stem);

/* Remove the folder tree at path (never following a link). */
void queue_study_remove_tree(const char *path);

/* 1 when dir/file exists (as any kind of entry). */
int queue_study_has(const char *dir, const char *file);

#endif
