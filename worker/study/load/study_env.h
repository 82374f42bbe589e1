/* study_env: what a reader needs to reproduce a study's figures: the command, the program (its
   version and a hash of its bytes), the compiler, the CPU and the machine's load when it ran. */
#ifndef STUDY_ENV_H
#define STUDY_ENV_H

#include "base/json.h"
#include "base/sbuf.h"

struct study_env {
    char command[1024]; /* the command line, arguments joined by spaces ("" unknown) */
    char version[32];   /* WORKER_VERSION */
    char program[20];   /* a hash of the program's own bytes, hex: names the build exactly */
    char compiler[96];  /* the compiler's version string */
    char cpu[128];      /* the CPU's model name ("" unknown) */
    int cores;          /* online processors */
    double load[3];     /* load average over 1, 5 and 15 minutes (-1 unknown) */
};

/* Fill env from this process and machine (/proc on Linux; what is unknown stays empty). */
void study_env_read(struct study_env *env);

/* env as a JSON object under key (as verdict.json's "reproducibility"). */
void study_env_json(struct json *j, const char *key, const struct study_env *env);

/* env as one HTML paragraph for a report. */
void study_env_html(struct sbuf *b, const struct study_env *env);

#endif
