/* cli: parse the command line's options and their values; print an error as one line. */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "job/procs.h"
#include "job/part.h"

int cli_takes_value(const char *a)
{
    static const char *const names[] = {
        "--out",           "--processes", "--queue",       "--poll",  "--retries",
        "--lease-timeout", "--part",      "--entry-cpu-s", "--entry", NULL};
    for (int i = 0; names[i]; i++)
        if (!strcmp(a, names[i]))
            return 1;
    return 0;
}

int cli_option_value(const char *a, const char *v, struct queue_opts *q)
{
    char *end = "";
    double d = v ? strtod(v, &end) : 0;
    int number = v && *v && !*end && strspn(v, "0123456789+-.eE") == strlen(v),
        whole = number && d == (long)d;
    if (!v) {
        err_print("worker: %s needs a value; see worker --help\n", a);
        return -1;
    } else if (!*v && (!strcmp(a, "--out") || !strcmp(a, "--queue"))) {
        /* "" would make OUT/<name> "/<name>": the file system's root */
        err_print("worker: %s needs a directory, got \"\"\n", a);
        return -1;
    } else if (!strcmp(a, "--out")) {
        q->run.out_dir = v;
    } else if (!strcmp(a, "--queue")) {
        q->dir = v;
    } else if (!strcmp(a, "--processes")) {
        if (!whole || d < 1 || d > PROCS_MAX_PROCESSES)
            goto bad;
        q->run.processes = (int)d;
    } else if (!strcmp(a, "--retries")) {
        if (!whole || d < 0 || d > 100)
            goto bad;
        q->retries = (int)d;
    } else if (!strcmp(a, "--poll") || !strcmp(a, "--lease-timeout")) {
        /* a lease is renewed every quarter of its timeout: under 0.1 s a busy machine's scheduling
           alone would let a live claim expire */
        if (!number || !(d > 0 && d <= 604800) || (a[2] == 'l' && d < 0.1))
            goto bad;
        *(a[2] == 'p' ? &q->poll_s : &q->lease_timeout_s) = d;
    } else if (!strcmp(a, "--entry")) {
        q->entry = v;
    } else if (!strcmp(a, "--entry-cpu-s")) {
        if (!number || !(d >= 0.01 && d <= 1e6))
            goto bad;
        q->entry_cpu_s = d;
    } else if (!strcmp(a, "--part")) {
        int i, parts, used = 0;
        if (sscanf(v, "%d/%d%n", &i, &parts, &used) != 2 || v[used] || parts < 1 || parts > PART_MAX ||
            i < 0 || i >= parts) {
            err_print("worker: --part must be I/N with 0 <= I < N <= %d, got \"%s\"\n", PART_MAX, v);
            return -1;
        }
        q->run.part = i;
        q->run.parts = parts;
    }
    return 0;
bad:
    err_print("worker: %s must be %s, got \"%s\"\n", a,
              !strcmp(a, "--processes")       ? "a whole number in [1, 256]"
              : !strcmp(a, "--retries")       ? "a whole number in [0, 100]"
              : !strcmp(a, "--lease-timeout") ? "a number of seconds in [0.1, 604800]"
              : !strcmp(a, "--entry-cpu-s")   ? "CPU seconds in [0.01, 1e6]"
                                              : "a number of seconds in (0, 604800]",
              v);
    return -1;
}

char **cli_split_equals(int *argc, char **argv)
{
    static const char *const diff_values[] = {"--max-rmse", "--block", "--map", NULL};
    char **out = calloc((size_t)*argc * 2 + 1, sizeof *out);
    int n = 0, ended = 0;
    if (!out)
        return NULL;
    for (int i = 0; i < *argc; i++) {
        char *a = argv[i], *eq = strchr(a, '=');
        int known = 0;
        ended |= i > 0 && !strcmp(a, "--");
        if (!ended && i > 0 && !strncmp(a, "--", 2) && eq) {
            *eq = 0;
            known = cli_takes_value(a);
            for (int k = 0; diff_values[k]; k++)
                known |= !strcmp(a, diff_values[k]);
            if (!known)
                *eq = '=';
        }
        out[n++] = a;
        if (known)
            out[n++] = eq + 1;
    }
    *argc = n;
    return out;
}

void cli_hoist_subcommand(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h") || !strcmp(argv[i], "--version") ||
            !strcmp(argv[i], "--")) {
            return;
        } else if (cli_takes_value(argv[i])) {
            i++;
        } else if (!(argv[i][0] == '-' && argv[i][1])) {
            if (i > 1 &&
                (!strcmp(argv[i], "diff") || !strcmp(argv[i], "points") || !strcmp(argv[i], "merge") ||
                 !strcmp(argv[i], "status") || !strcmp(argv[i], "requeue") || !strcmp(argv[i], "verdict") ||
                 !strcmp(argv[i], "plan"))) {
                char *sub = argv[i];
                memmove(&argv[2], &argv[1], (size_t)(i - 1) * sizeof *argv);
                argv[1] = sub;
            }
            return;
        }
    }
}

void cli_print_err(const struct err *e)
{
    char buf[4096];
    err_format(e, buf, sizeof buf);
    fprintf(stderr, "%s\n", buf);
}
