/* machine: the host and CPU model a render ran on, recorded in its sidecar so that a study whose
   images came from several machines can say its CPU times are not comparable. */
#ifndef MACHINE_H
#define MACHINE_H

#include <stddef.h>

#define MACHINE_TEXT_MAX 128

struct machine {
    char host[MACHINE_TEXT_MAX];      /* gethostname(), "unknown" when it fails */
    char cpu_model[MACHINE_TEXT_MAX]; /* /proc/cpuinfo's first "model name" (or "Hardware", "cpu
                                         model", "Processor"), "unknown" when there is none */
};

/* This machine's host name and CPU model, printable ASCII only. */
void machine_describe(struct machine *m);

#endif
