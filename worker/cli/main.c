/* main: the `worker` command line: parse, dispatch, print, exit. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "diff.h"
#include "dryrun.h"
#include "entry.h"
#include "rejudge.h"
#include "study/run/jobfile_run.h"
#include "study/run/study_fan.h"
#include "job/job.h"
#include "job/jobfile.h"
#include "job/outdir.h"
#include "plan.h"
#include "points.h"
#include "farm/merge.h"
#include "farm/queue.h"
#include "farm/queue_requeue.h"
#include "farm/queue_status.h"
#include "farm/spread_plan.h"
#include "job/run.h"

static const char usage[] =
    "usage: worker JOB.yaml [JOB.yaml ...]     render each job file, in order\n"
    "       worker JOB.yaml --part I/N         render rows with row % N == I into a part file\n"
    "                                          (a compare job: its images with index % N == I)\n"
    "       worker STUDY.yaml --entry NAME     render one entry of `worker plan`'s (a batch array's task)\n"
    "       worker JOB.yaml --dry-run          samples, memory and CPU time from a short pilot;\n"
    "                                          renders nothing, writes nothing\n"
    "       worker plan JOB.yaml [--workers N] [--cores C] [--json]  a study's queue entries, their\n"
    "                                          estimated CPU and its wall time on a farm; writes nothing\n"
    "       worker merge JOB.yaml              merge a job's part files into its image\n"
    "       worker --queue DIR [--once] [--poll S] [--retries N] [--lease-timeout S] [--entry-cpu-s S]\n"
    "                                          drain DIR; outputs in DIR/done/ (--once: exit when empty)\n"
    "       worker status DIR [--json]         a queue's waiting, running, done and failed jobs, studies\n"
    "       worker requeue DIR NAME... | --failed  move failed (or done) jobs back into the queue\n"
    "       worker diff A B [--json] [--map F.png] [--max-rmse X] [--block N]\n"
    "                                          error of B against reference A (EXR, PFM, PNG, PPM)\n"
    "       worker verdict DIR [--json] [--quiet]  judge a compare output folder again from its summary.csv\n"
    "       worker points SAMPLER THRESHOLD [--seed S] [--svg F]  print a point set as CSV\n"
    "              [--sets M] [--spectrum F.png] [--radial F.svg] [--stats]  and its spectrum, statistics\n"
    "              [--padded K]                a pixel's K padded dimensions (sampler_dims: all)\n"
    "       worker --help | --version\n"
    "options: --out DIR (default ./out)  --processes N (overrides the job)  --quiet\n"
    "         --force (render even when the outputs are current)\n"
    "         --opt=VALUE works as --opt VALUE; -- ends the options\n"
    "queue defaults: --poll 2 (seconds between scans when idle)  --retries 1  --lease-timeout 60\n"
    "                --entry-cpu-s 60 (a study's render above it is cut into row parts)\n";

static const char help[] =
    "worker: a batch render worker around a Monte Carlo path tracer for studying samplers.\n"
    "\n"
    "Each job file (YAML) names a scene, a pixel sampler and its threshold (the minimum spacing in\n"
    "a 100x100 domain). The samplers, with their samples per pixel at threshold 1:\n"
    "%s\n"
    "Rows are split over forked processes; the image (PNG or PPM: 8-bit display values; EXR or\n"
    "PFM: linear radiance) and a JSON stats sidecar land in OUT/<job name>/.\n"
    "\n"
    "A compare job is a job file with variants: (and optionally scenes:, sweep:, seeds:): it\n"
    "renders every combination, scores each against a reference render and writes the images,\n"
    "summary.csv, chart.svg (error against CPU time), report.html (opening with the verdict:\n"
    "rankings at equal samples and CPU time, ties unless Welch's t test, Holm-corrected at 0.05,\n"
    "tells the seeds apart; failure modes, bias among them) and\n"
    "verdict.json in OUT/<name>/; docs/compare.md. A job file with studies: [a.yaml, ...] (a\n"
    "suite) runs those compare jobs as one, each into OUT/<name>/<study>/, with one verdict.\n"
    "A queue (--queue DIR) is a folder of job files that any number of workers, on one machine\n"
    "or many sharing it, drain: outputs in DIR/done/<name>/, failed jobs in DIR/failed/.\n"
    "--part I/N and merge split one job's rows over machines and join them again.\n"
    "--dry-run prints a job's (or compare job's) samples, memory and CPU time from a short\n"
    "pilot, and a compare job's too-weak reference, rendering and writing nothing.\n"
    "worker verdict DIR re-judges a compare job's or suite's output folder from its summary.csv\n"
    "(images where present; it names the checks it skipped; --json: verdict.json's text).\n"
    "worker diff scores an image against a reference (in linear radiance for EXR/PFM, see\n"
    "docs/formats.md); worker points prints (or draws, --svg)\n"
    "one point set of a sampler.\n"
    "\n"
    "formats: docs/job-format.md, docs/scene-format.md (every key, with examples)\n"
    "more:    docs/compare.md, docs/farm.md, docs/samplers.md (in the source tree)\n"
    "\n"
    "exit status: 0 all jobs done, 1 a job failed while rendering, 2 bad usage or bad input.\n";

/* help's sampler list and each kind's samples per pixel at threshold 1, from sampler_kind.c's rows */
static void print_help(void)
{
    char spp[512];
    size_t used = 0, line = 0;
    for (const char *const *k = sampler_kind_names(); *k && used < sizeof spp; k++) {
        enum sampler_kind kind;
        sampler_kind_parse(*k, &kind);
        char item[64];
        int w = snprintf(item, sizeof item, "%s %s%.0f", *k,
                         sampler_traits(kind)->count == SAMPLER_COUNT_BRIDSON ? "about " : "",
                         sampler_expected_spp(kind, 1.0));
        const int wrap = used - line + (size_t)w > 90;
        w = snprintf(spp + used, sizeof spp - used, "%s%s", used == 0 ? "  " : wrap ? ",\n  " : ", ", item);
        used += w > 0 ? (size_t)w : 0;
        if (wrap)
            line = used - strlen(item) - 2;
    }
    printf(help, spp);
    printf("\n%s", usage);
}

static int max_rc(int a, int b)
{
    return a > b ? a : b;
}

/* The job files of one command line taken so far, by name: two files of one name would write the
   same OUT/<name>/, the later replacing the earlier's outputs. */
struct named {
    char name[JOB_NAME_MAX];
    const char *path;
    dev_t dev;
    ino_t ino;
};

/* A job's name against the command line's others (jobfile_run's name_ok): the job files taken
   so far (taken, ntaken of them) and the one at path now. */
struct names_seen {
    const char *path;
    const struct run_opts *o;
    struct named *taken;
    int ntaken;
};

/* 0 (said on stderr) when name is another job file's among those taken; else 1, and it is taken. */
static int name_ok(const char *name, void *arg)
{
    struct names_seen *ns = arg;
    struct named *taken = ns->taken;
    struct stat st;
    if (stat(ns->path, &st) < 0)
        st.st_dev = 0, st.st_ino = 0;
    for (int i = 0; i < ns->ntaken; i++) {
        if (strcmp(taken[i].name, name) != 0)
            continue;
        if (taken[i].dev == st.st_dev && taken[i].ino == st.st_ino) /* the same file again */
            return 1;
        err_print("%s: name \"%s\" is also the name of %s, earlier on this command line: its outputs in "
                  "%s/%s/ would replace that job's (give one of them another name: in its file)",
                  ns->path, name, taken[i].path, ns->o->out_dir, name);
        return 0;
    }
    taken[ns->ntaken] = (struct named){.path = ns->path, .dev = st.st_dev, .ino = st.st_ino};
    snprintf(taken[ns->ntaken++].name, sizeof taken[0].name, "%s", name);
    return 1;
}

/* What a plain job's run or merge ended with, on stderr. */
static void print_outcome(const struct job *j, int merge, int rc, struct run_result *rr, struct err *e)
{
    if (rc != 0) {
        if (rc == 2 && !e->file[0]) /* bad input found while rendering (memory, --out): whose */
            snprintf(e->file, sizeof e->file, "%s", j->path);
        if (rc == 1) { /* a render failure names the job; bad input names its file */
            char why[sizeof e->msg];
            snprintf(why, sizeof why, "%s", e->msg);
            snprintf(e->msg, sizeof e->msg, "%s: %s; nothing written", j->name, why);
        }
        cli_print_err(e);
    } else if (rr->skipped) {
        err_print("%s: up to date (%s, same job hash), skipped; --force renders it again\n", j->name,
                  rr->out.image[0]);
    } else if (merge) {
        err_print("%s: merged %d parts, %dx%d -> %s\n", j->name, rr->procs.processes, rr->width, rr->height,
                  rr->out.image[0]);
        run_print_warnings(j, rr);
    } else {
        run_print_summary(j, rr);
    }
}

/* Render (or, with merge, merge the parts of) the job file at path, read once; its exit status.
   ns: the jobs of this command line so far (name_ok), compare jobs included. */
static int job_main(const char *path, const struct run_opts *o, int merge, struct names_seen *ns)
{
    struct jobfile f;
    struct jobfile_outcome out = {0};
    struct err e;
    int rc = 2;
    ns->path = path;
    if (jobfile_open(&f, path, path, &e) < 0) {
        cli_print_err(&e);
    } else if (f.kind != JOBFILE_PLAIN && merge) {
        err_print("%s: a compare job renders whole images: no merge\n", path);
    } else if (f.kind != JOBFILE_PLAIN && o->parts) { /* a batch task's share of the study's renders */
        rc = study_fan_share(&f, o);
    } else if (merge) {
        if (name_ok(f.job.name, ns)) {
            rc = merge_parts(&f.job, o, &out.rr, &out.e);
            print_outcome(&f.job, 1, rc, &out.rr, &out.e);
        }
    } else {
        rc = jobfile_run(&f, o, name_ok, ns, &out);
        if (f.kind == JOBFILE_PLAIN && !(rc == 2 && !out.e.msg[0])) /* not refused by name_ok */
            print_outcome(&f.job, 0, rc, &out.rr, &out.e);
    }
    jobfile_close(&f);
    return rc;
}

/* main after cli_split_equals: dispatch to a subcommand or render the jobs; the exit status. */
static int worker_main(int argc, char **argv)
{
    static const struct {
        const char *name;
        int (*run)(int, char **); /* the subcommand's main, given argv from its name */
    } subcommands[] = {{"points", points_main},       {"diff", diff_main}, {"verdict", rejudge_main},
                       {"status", queue_status_main}, {"plan", plan_main}, {"requeue", queue_requeue_main}};
    cli_hoist_subcommand(argc, argv);
    for (size_t i = 0; argc >= 2 && i < sizeof subcommands / sizeof subcommands[0]; i++)
        if (!strcmp(argv[1], subcommands[i].name))
            return subcommands[i].run(argc - 1, argv + 1);
    struct queue_opts q = {.poll_s = QUEUE_POLL_S,
                           .retries = QUEUE_RETRIES,
                           .lease_timeout_s = QUEUE_LEASE_TIMEOUT_S,
                           .entry_cpu_s = SPREAD_PLAN_ENTRY_CPU_S,
                           .run = {.out_dir = OUTDIR_DEFAULT, .progress = isatty(2)}};
    struct run_opts *o = &q.run;
    int merge = argc >= 2 && !strcmp(argv[1], "merge");
    const char **jobs = calloc((size_t)argc, sizeof *jobs);
    int njobs = 0, worst = 0, out_given = 0, dry_run = 0;
    const char *queue_only = NULL; /* the first option that only a queue uses */
    if (!jobs)
        return 2;
    int options_ended = 0; /* after "--" every argument is a job file */
    for (int i = 1 + merge; i < argc; i++) {
        const char *a = argv[i];
        if (!options_ended && !strcmp(a, "--")) {
            options_ended = 1;
            continue;
        } else if (options_ended) {
            jobs[njobs++] = a;
            continue;
        }
        if (!queue_only && (!strcmp(a, "--once") || !strcmp(a, "--poll") || !strcmp(a, "--retries") ||
                            !strcmp(a, "--lease-timeout") || !strcmp(a, "--entry-cpu-s")))
            queue_only = a;
        out_given |= !strcmp(a, "--out");
        if ((!strcmp(a, "--help") || !strcmp(a, "-h")) && merge) {
            printf("usage: worker merge JOB.yaml [--out DIR] [--quiet]\n"
                   "join the part files a job's --part I/N renders wrote (OUT/<name>/) into its image and "
                   "sidecar\n");
            goto out;
        } else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            print_help();
            goto out;
        } else if (!strcmp(a, "--version")) {
            printf("worker %s\n", WORKER_VERSION);
            goto out;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            o->quiet = 1;
        } else if (!strcmp(a, "--once")) {
            q.once = 1;
        } else if (!strcmp(a, "--force")) {
            o->force = 1;
        } else if (!strcmp(a, "--dry-run")) {
            dry_run = 1;
        } else if (cli_takes_value(a)) {
            if (cli_option_value(a, i + 1 < argc ? argv[++i] : NULL, &q) < 0) {
                worst = 2;
                goto out;
            }
        } else if (a[0] == '-' && a[1]) {
            err_print("worker: unknown option %s; see worker --help\n", a);
            worst = 2;
            goto out;
        } else {
            jobs[njobs++] = a;
        }
    }
    /* --out DIR/ (a shell's completion adds the slash) is DIR: no "DIR//<name>" in paths shown */
    char out_dir[4096];
    snprintf(out_dir, sizeof out_dir, "%s", o->out_dir);
    for (size_t n = strlen(out_dir); n > 1 && out_dir[n - 1] == '/'; n--)
        out_dir[n - 1] = 0;
    o->out_dir = out_dir;
    /* accepted, but a user who gave them expects something of them: say they do nothing */
    if (q.dir && out_given)
        err_print("worker: --out is ignored with --queue: outputs go to %s/done/<name>/\n", q.dir);
    if (!q.dir && queue_only)
        err_print("worker: %s is ignored without --queue\n", queue_only);
    if (dry_run && (q.dir || merge || o->parts)) {
        err_print("worker: --dry-run estimates job files: no --queue, merge or --part; see worker --help\n");
        worst = 2;
    } else if (dry_run && njobs == 0) {
        err_print("worker: --dry-run needs a job file; see worker --help\n");
        worst = 2;
    } else if (dry_run) {
        for (int i = 0; i < njobs; i++)
            worst = max_rc(worst, dryrun_main(jobs[i], o));
    } else if (q.entry && (q.dir || merge || o->parts || njobs != 1)) {
        err_print("worker: --entry renders one entry of one study: no --queue, merge or --part; see worker "
                  "--help\n");
        worst = 2;
    } else if (q.entry) {
        worst = entry_main(jobs[0], q.entry, o);
    } else if (q.dir && (njobs || merge || o->parts)) {
        err_print("worker: --queue takes no job files, merge or --part; see worker --help\n");
        worst = 2;
    } else if (q.dir) {
        queue_signals_install();
        worst = queue_main(&q);
    } else if (njobs == 0) {
        err_print("worker: no job file given; see worker --help\n");
        worst = 2;
    } else if (merge && o->parts) {
        err_print("worker: merge finds the parts itself; --part is for rendering one; see worker --help\n");
        worst = 2;
    } else {
        struct names_seen ns = {NULL, o, calloc((size_t)njobs, sizeof *ns.taken), 0};
        for (int i = 0; ns.taken && i < njobs; i++)
            worst = max_rc(worst, job_main(jobs[i], o, merge, &ns));
        if (!ns.taken) {
            err_print("worker: out of memory");
            worst = 2;
        }
        free(ns.taken);
    }
out:
    free(jobs);
    return worst;
}

int main(int argc, char **argv)
{
    /* A file-size limit must fail our write() with EFBIG (reported, temp file removed), not
       kill the process half-way through an output. */
    signal(SIGXFSZ, SIG_IGN);
    char **args = cli_split_equals(&argc, argv);
    if (!args)
        return 2;
    int rc = worker_main(argc, args);
    free(args);
    return rc;
}
