/* queue_requeue: `worker requeue DIR`, job files put back into a queue by people (SPEC "Additions"). */
#ifndef QUEUE_REQUEUE_H
#define QUEUE_REQUEUE_H

/* worker requeue DIR NAME... | --failed, with argv[0] = "requeue": move the job files NAME (X or
   X.yaml) from failed/ (or done/) back to DIR, never over a job waiting or running under that
   name, their logs removed; NAME of a study in progress (DIR/spread/X/) puts its failed renders
   back; --failed does both for everything failed. One line per job on stderr. Exit 0 every one
   moved, 2 bad usage or one could not be moved (failed/ unreadable included). */
int queue_requeue_main(int argc, char **argv);

#endif
