/* queue_study_key: what a study's folder DIR/spread/<stem>/ must hold, and the check of it: study.key
   records the hash of the job's bytes and the name of every entry written; everything read back later
   is checked against it and against the kind of file it must be (never a symbolic link), so that a
   changed, forged or removed file is said in one line rather than trusted. */
#ifndef QUEUE_STUDY_KEY_H
#define QUEUE_STUDY_KEY_H

#include <stddef.h>
#include <stdint.h>

#include "base/sbuf.h"

/* The record, loaded: the job's hash and its entries' names (sorted). */
struct study_key {
    uint64_t job_hash;
    char (*entry)[32];
    int n;
};

/* Where a study stands, from its folder's files. */
enum queue_study_state {
    QUEUE_STUDY_SPREADING, /* made, its job file not yet filed in job/ (its claim is in DIR/running/) */
    QUEUE_STUDY_ACTIVE,    /* its job file in job/: entries to render, then the gather */
    QUEUE_STUDY_GATHERED,  /* gathered (its job file in DIR/done/), the gather entry not yet filed */
    QUEUE_STUDY_FINISHED,  /* the gather entry filed in done/ */
    QUEUE_STUDY_DAMAGED    /* a file is not what was written (why says which) */
};

/* Start the record of a study spreading job (len bytes) in *b; add its entries with
   queue_study_key_add, then write the text as study.key. */
void queue_study_key_begin(struct sbuf *b, const uint8_t *job, size_t len);
void queue_study_key_add(struct sbuf *b, const char *entry);

/* 1 when entry is one the study's record names. */
int queue_study_key_has(const struct study_key *k, const char *entry);

void queue_study_key_free(struct study_key *k);

/* Where the study in folder sd (of queue dir, job file stem.yaml) stands; its record into *k
   (freed by the caller, also when damaged), and when damaged one line into why saying what is wrong.
   With hash_jobs, study.job's and job/X.yaml's bytes are checked against the record too (status); a
   worker checks them as it reads them, once (queue_entry). */
enum queue_study_state queue_study_state(const char *dir, const char *sd, const char *stem,
                                         struct study_key *k, int hash_jobs, char *why, size_t n);

/* 1 when the regular file path (never through a link) holds bytes of hash h. */
int queue_study_key_same(const char *path, uint64_t h);

#endif
