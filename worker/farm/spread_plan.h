/* spread_plan: the entries a compare job or suite spread over a queue is cut into (each reference's
   two halves and each image, one over the CPU target cut into row parts), sized by the cost model, in
   claim order (references first, then the longest), and the study's wall time on W workers of C
   cores. Shared by the queue's spread (queue_study.h) and `worker plan`. */
#ifndef SPREAD_PLAN_H
#define SPREAD_PLAN_H

#include <stddef.h>

#include "study/run/study_fan.h"

/* An entry's CPU target when neither the job (entry_cpu_s:) nor the queue (--entry-cpu-s) gives one. */
#define SPREAD_PLAN_ENTRY_CPU_S 60.0
/* The cost model's measuring budget in CPU seconds, all pilots of a spread together. */
#define SPREAD_PLAN_BUDGET_S 3.0

struct spread_entry {
    char name[64];            /* the entry file's name: a-ref-K-S-H[-pI-N].yaml, b-img-K-IIIII[-pI-N].yaml */
    enum study_fan_kind kind; /* a reference's half, or an image */
    int k, index, half;       /* study k's scene `index` (half 0 or 1), or its image `index` */
    int part, parts;          /* parts 1: the whole render */
    int processes;            /* the render processes it runs with */
    double est_cpu_s;         /* its share of the render's estimated CPU seconds */
};

struct spread_plan {
    struct spread_entry *e; /* owned, in claim order */
    int n, cap;             /* cap: entries allocated */
    double total_cpu_s;
};

/* Plan the study f: every render estimated (seeds cost alike: once per seedless combination) with
   `processes` processes (0: each job's), cut for an entry CPU target of each study's entry_cpu_s:
   or else target_s. 0, or -1 with e filled (a scene the render would refuse, no memory). Free
   with spread_plan_free (accepts a zeroed plan). */
int spread_plan_make(const struct study_fan *f, double target_s, int processes, struct spread_plan *p,
                     struct err *e);
void spread_plan_free(struct spread_plan *p);

/* The file a spread study's folder keeps its plan in (one line an entry, in claim order:
   "<est_cpu_s> <processes> <kind a|b> <name>"), for worker status. */
#define SPREAD_PLAN_FILE "plan.txt"

/* p as that text (malloc'd; NULL on no memory). */
char *spread_plan_text(const struct spread_plan *p);

/* The plan file at path read back into p (est_cpu_s, processes, kind and name of each entry; lines
   that do not parse are passed over). 0, or -1 when it cannot be read. Free with spread_plan_free. */
int spread_plan_read(const char *path, struct spread_plan *p);

/* Read an entry file's name back: its kind, indices and part (parts 1: whole). 0, or -1 when it
   is not one (the gather, or a name no plan makes). */
int spread_plan_parse(const char *name, struct spread_entry *out);

/* The predicted wall seconds of the n entries e (in claim order) on `workers` workers of `cores`
   cores each: each entry taken by the first free worker, images once every reference has ended,
   its wall its CPU over min(its processes, cores). The gather after them is not counted (it
   renders nothing). */
double spread_plan_makespan(const struct spread_entry *e, int n, int workers, int cores);

#endif
