/* cli: the command line's options: `--opt=VALUE` split, a subcommand after leading options moved
   first, and each option with a value checked into struct queue_opts (usage errors on stderr). */
#ifndef CLI_H
#define CLI_H

#include "base/err.h"
#include "farm/queue.h"

/* 1 when a is an option that takes a value (cli.c's list: --out, --processes, --queue, ...). */
int cli_takes_value(const char *a);

/* One option a with its value v into q. 0, or -1 after printing the usage error. */
int cli_option_value(const char *a, const char *v, struct queue_opts *q);

/* `--out=DIR` as `--out DIR` (GNU style, as pbrt and Slurm take it too) for every option that
   takes a value, diff's included; a job file's name is never split, nor anything after "--".
   The new argv (argc grown by one per split) is malloc'ed; NULL when out of memory. */
char **cli_split_equals(int *argc, char **argv);

/* `worker --quiet diff A B`: a subcommand after leading options is moved to argv[1], the options
   after it, where its own parser judges them; after --help or --version nothing moves. */
void cli_hoist_subcommand(int argc, char **argv);

/* e as one line on stderr (err_format's "file:line:col: msg"). */
void cli_print_err(const struct err *e);

#endif
