/* plan: `worker plan JOB.yaml`: the entries a queue would spread a compare job or suite into, each
   with its estimated CPU, and the study's predicted wall time on a farm; nothing rendered or written. */
#include "plan.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/json.h"
#include "cli.h"
#include "farm/spread_plan.h"
#include "job/jobfile.h"

static const char plan_usage[] =
    "usage: worker plan JOB.yaml [--workers N] [--cores C] [--entry-cpu-s S] [--processes N] [--json]\n";

static const char plan_help[] =
    "worker plan: the entries a queue would spread a compare job or suite into (each settings\n"
    "reference's two halves, each image; a render whose estimated CPU exceeds the entry target cut\n"
    "into row parts), in the order workers claim them (references first, then the longest), each\n"
    "with its estimated CPU seconds from the cost model (as --dry-run's, measured on this machine),\n"
    "and the predicted wall time (makespan) of the study on N workers of C cores like this machine.\n"
    "Renders nothing, writes nothing; takes a few seconds of CPU at most.\n"
    "  --workers N       workers draining the queue (default 1)\n"
    "  --cores C         cores of each (default this machine's)\n"
    "  --entry-cpu-s S   the entry target when the job gives no entry_cpu_s: (default 60)\n"
    "  --processes N     render processes per entry (default each job's), as a queue's --processes\n"
    "  --json            entries[] (name, kind, study, index, half, part, parts, est_cpu_s), total_cpu_s\n"
    "                    and makespan_s as JSON\n";

/* A whole number in [lo, hi] from text, or -1. */
static long whole(const char *text, long lo, long hi)
{
    char *end;
    errno = 0;
    long v = text ? strtol(text, &end, 10) : -1;
    return text && !errno && end != text && !*end && v >= lo && v <= hi ? v : -1;
}

struct plan_args {
    const char *path;
    long workers, cores, processes;
    double target_s;
    int json;
};

/* The options into a; 0, 1 after --help, or 2 after a line on stderr. */
static int parse(int argc, char **argv, struct plan_args *a)
{
    long here = sysconf(_SC_NPROCESSORS_ONLN);
    *a = (struct plan_args){.workers = 1, .cores = here > 0 ? here : 1, .target_s = SPREAD_PLAN_ENTRY_CPU_S};
    int ended = 0; /* after "--" every argument is the job file */
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        char *end;
        if (!ended && !strcmp(o, "--")) {
            ended = 1;
        } else if (ended || o[0] != '-' || !o[1]) {
            if (a->path) {
                fprintf(stderr, "worker plan: one job file at a time (got %s and %s)\n", a->path, o);
                return 2;
            }
            a->path = o;
        } else if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
            printf("%s\n%s", plan_usage, plan_help);
            return 1;
        } else if (!strcmp(o, "--json")) {
            a->json = 1;
        } else if (!strcmp(o, "--workers") || !strcmp(o, "--cores") || !strcmp(o, "--processes")) {
            long n = whole(v, 1, o[2] == 'w' ? 100000 : 4096);
            if (n < 0) {
                fprintf(stderr, "worker plan: %s: needs a whole number from 1 to %d, got %s\n", o,
                        o[2] == 'w' ? 100000 : 4096, v ? v : "nothing");
                return 2;
            }
            *(o[2] == 'w' ? &a->workers : o[2] == 'c' ? &a->cores : &a->processes) = n;
            i++;
        } else if (!strcmp(o, "--entry-cpu-s")) {
            errno = 0;
            a->target_s = v ? strtod(v, &end) : 0;
            if (!v || errno || end == v || *end || !(a->target_s >= 0.01 && a->target_s <= 1e6)) {
                fprintf(stderr, "worker plan: --entry-cpu-s: needs CPU seconds in [0.01, 1e6], got %s\n",
                        v ? v : "nothing");
                return 2;
            }
            i++;
        } else {
            fprintf(stderr, "worker plan: unknown option %s\n%s", o, plan_usage);
            return 2;
        }
    }
    if (!a->path) {
        fprintf(stderr, "worker plan: needs a job file\n%s", plan_usage);
        return 2;
    }
    return 0;
}

/* What entry x renders, in words: "checker reference half a, part 3/9". */
static void entry_words(const struct study_fan *f, const struct spread_entry *x, char *buf, size_t n)
{
    const struct compare *c = study_fan_study(f, x->k);
    char part[32] = "";
    if (x->parts > 1)
        snprintf(part, sizeof part, ", part %d/%d", x->part + 1, x->parts);
    if (x->kind == STUDY_FAN_REFERENCE)
        snprintf(buf, n, "%s: reference of %s, half %c%s", c->name, c->scenes[x->index].name, "ab"[x->half],
                 part);
    else
        snprintf(buf, n, "%s: %s%s", c->name, c->items[x->index].job.output, part);
}

static void print_json(const struct study_fan *f, const struct spread_plan *p, const struct plan_args *a,
                       double makespan_s)
{
    struct json j;
    char words[512];
    json_init(&j);
    json_begin_object(&j, NULL);
    json_string(&j, "name", study_fan_name(f));
    json_uint(&j, "workers", (uint64_t)a->workers);
    json_uint(&j, "cores", (uint64_t)a->cores);
    json_number(&j, "entry_cpu_s", a->target_s);
    json_number(&j, "total_cpu_s", p->total_cpu_s);
    json_number(&j, "makespan_s", makespan_s);
    json_begin_array(&j, "entries");
    for (int i = 0; i < p->n; i++) {
        const struct spread_entry *x = &p->e[i];
        entry_words(f, x, words, sizeof words);
        json_begin_object(&j, NULL);
        json_string(&j, "name", x->name);
        json_string(&j, "kind", x->kind == STUDY_FAN_REFERENCE ? "reference" : "image");
        json_string(&j, "render", words);
        json_uint(&j, "study", (uint64_t)x->k);
        json_uint(&j, "index", (uint64_t)x->index);
        if (x->kind == STUDY_FAN_REFERENCE)
            json_uint(&j, "half", (uint64_t)x->half);
        json_uint(&j, "part", (uint64_t)x->part);
        json_uint(&j, "parts", (uint64_t)x->parts);
        json_uint(&j, "processes", (uint64_t)x->processes);
        json_number(&j, "est_cpu_s", x->est_cpu_s);
        json_end_object(&j);
    }
    json_end_array(&j);
    json_end_object(&j);
    if (j.text.buf)
        printf("%s\n", j.text.buf);
    json_free(&j);
}

static void print_text(const struct study_fan *f, const struct spread_plan *p, const struct plan_args *a,
                       double makespan_s)
{
    char words[512];
    int refs = 0;
    double largest = 0;
    for (int i = 0; i < p->n; i++) {
        refs += p->e[i].kind == STUDY_FAN_REFERENCE;
        largest = p->e[i].est_cpu_s > largest ? p->e[i].est_cpu_s : largest;
    }
    printf("%s: plan: nothing rendered, nothing written\n", study_fan_name(f));
    printf("  entries   %d (%d of references, %d of images), then the gather; target %g CPU s an entry\n",
           p->n, refs, p->n - refs, a->target_s);
    for (int i = 0; i < p->n; i++) {
        entry_words(f, &p->e[i], words, sizeof words);
        printf("  %-28s %9.1f s CPU  %s\n", p->e[i].name, p->e[i].est_cpu_s, words);
    }
    printf("  CPU time  about %.0f s in all, the largest entry %.1f s\n", p->total_cpu_s, largest);
    printf("  wall      about %.0f s (%.1f min) on %ld worker%s of %ld core%s like this machine\n",
           makespan_s, makespan_s / 60, a->workers, a->workers == 1 ? "" : "s", a->cores,
           a->cores == 1 ? "" : "s");
}

int plan_main(int argc, char **argv)
{
    struct plan_args a;
    int rc = parse(argc, argv, &a);
    if (rc)
        return rc == 1 ? 0 : rc;
    struct jobfile jf;
    struct study_fan f = {0};
    struct spread_plan p = {0};
    struct err e = {0};
    rc = 2;
    if (jobfile_open(&jf, a.path, a.path, &e) < 0) {
    } else if (jf.kind == JOBFILE_PLAIN) {
        err_set(&e, a.path, 0, 0,
                "a plain job is one entry of a queue, rendered whole: see worker %s --dry-run for its cost",
                a.path);
    } else if (study_fan_load(&jf, &f, &e) == 0 &&
               spread_plan_make(&f, a.target_s, (int)a.processes, &p, &e) == 0) {
        double makespan_s = spread_plan_makespan(p.e, p.n, (int)a.workers, (int)a.cores);
        (a.json ? print_json : print_text)(&f, &p, &a, makespan_s);
        rc = 0;
    }
    if (rc)
        cli_print_err(&e);
    spread_plan_free(&p);
    study_fan_free(&f);
    jobfile_close(&jf);
    return rc;
}
