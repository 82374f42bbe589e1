/* plan: `worker plan JOB.yaml`: the entries a queue would spread a compare job or suite into, sized
   by the cost model, and its predicted wall time on a farm; nothing rendered, nothing written. */
#ifndef PLAN_H
#define PLAN_H

/* argv[0] is "plan". The exit status: 0, or 2 after one line on stderr (bad option or job). */
int plan_main(int argc, char **argv);

#endif
