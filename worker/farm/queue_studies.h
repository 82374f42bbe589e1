/* queue_studies: the studies in progress in a queue (DIR/spread/<stem>/, queue_study.h) as status and
   requeue see them: one line each with its renders done of all, failed, and an ETA. */
#ifndef QUEUE_STUDIES_H
#define QUEUE_STUDIES_H

struct queue_studies_entry {
    char file[256];                     /* the job file, X.yaml */
    char name[256];                     /* the study's folder name: the file's stem */
    int renders, done, failed, running; /* render entries (references and images; not the gather) */
    int gathering;                      /* its gather entry is claimed */
    double elapsed_s, eta_s;            /* since it was spread; ETA from the pace so far (< 0 unknown) */
    int waits_requeue;                  /* failed renders: it cannot finish until they are requeued */
    char damaged[1024];                 /* its folder is not as written: what is wrong ("" when sound) */
    int planned;                        /* its folder holds the plan (spread_plan.h): the figures below */
    double cpu_done_s, cpu_left_s;      /* estimated CPU seconds of its entries done, and not done */
    int lease_workers;                  /* workers holding a lease in the queue now (claims in running/) */
    double finish_s;                    /* predicted wall seconds to its last entry on those workers of
                                           this machine's cores (< 0 unknown: none holds a lease) */
};

/* The studies in progress under dir/spread/ into *out (malloc'd), by name; their count, or -1 when
   dir/spread/ exists but cannot be read (errno). */
int queue_studies_list(const char *dir, struct queue_studies_entry **out);

/* Move the failed render entries of the study of job file `file` (X.yaml) back to its waiting
   entries, their logs removed (an entry that was no regular file is written anew). The number
   moved; -1 when no study of that file is in progress; -2 when one could not be moved (said on
   stderr). */
int queue_studies_requeue(const char *dir, const char *file);

#endif
