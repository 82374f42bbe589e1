/* queue_study: a compare job or suite in a queue spread over its workers. The worker that claims
   it writes one render entry per reference and per image into DIR/study/<stem>/ (a queue of its
   own: running/, done/, failed/, with the same claims, leases, retries and recovery) and files the
   job there (job/<X>.yaml); workers drain those entries, references first; the entry claimed last
   gathers summary.csv, chart, report and verdict into done/<name>/, then files the job file in
   done/. */
#ifndef QUEUE_STUDY_H
#define QUEUE_STUDY_H

#include "queue_claim.h"

/* The folder below DIR that holds the studies in progress. */
#define QUEUE_STUDY_DIR "study"

/* The three kinds of entry, named so that claim order is their order: a-ref-K-S.yaml (study K's
   reference of scene S), b-img-K-I.yaml (its image I), c-gather.yaml. */
#define QUEUE_STUDY_GATHER "c-gather.yaml"

/* Spread the claimed compare job DIR/running/name (read from `from`, its paths as at `as`, stem
   its file's stem) over the queue; an invalid one goes to failed/ as any job. */
void queue_study_expand(struct queue *q, const char *name, const char *from, const char *as,
                        const char *stem);

/* Take and process one render entry of a study in progress. 1 when one was processed; 2 when none
   can be taken now but one will once the renders of an earlier kind running elsewhere are filed;
   0 when there is none. */
int queue_study_work(struct queue *q);

/* 1 when the study folder's entry `ticket` may be claimed: no entry of an earlier kind is waiting,
   running or failed. */
int queue_study_claimable(const char *study_dir, const char *ticket);

#endif
