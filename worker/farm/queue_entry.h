/* queue_entry: one claimed entry of a study spread over a queue (queue_study.h), processed: its
   reference or image rendered, or the study gathered, then the entry filed. */
#ifndef QUEUE_ENTRY_H
#define QUEUE_ENTRY_H

#include <stddef.h>

#include "queue_claim.h"
#include "queue_study_key.h"

/* Process the entry `ticket` of the study in sd (job file stem.yaml, its record k) claimed into its
   queue sq, and file it. When the study's job file read back is not the one its record names
   (changed since the study was spread), nothing is rendered or filed: the entry goes back to the
   study's waiting entries and damaged (n bytes) says what is wrong, for the caller to end the study;
   else damaged is "". */
void queue_entry_process(struct queue *q, struct queue *sq, const char *sd, const char *stem,
                         const struct study_key *k, const char *ticket, char *damaged, size_t n_damaged);

#endif
