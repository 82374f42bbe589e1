/* queue_drain: a worker draining the studies spread over its queue (queue_study.h): each study's
   folder DIR/spread/<stem>/ is a queue of its own whose entries are taken with the same claims,
   leases, retries and recovery, references first, images next, the gather last. */
#ifndef QUEUE_DRAIN_H
#define QUEUE_DRAIN_H

#include "queue_claim.h"

/* Take and process one render entry of a study in progress. 1 when one was processed; 2 when none
   can be taken now but one will once the renders of an earlier kind running elsewhere are filed;
   0 when there is none (a study whose earlier renders failed waits for a requeue). */
int queue_drain_work(struct queue *q);

#endif
