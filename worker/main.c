/* main: the `worker` command line (SPEC "Command line"): parse, dispatch, print, exit. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "compare.h"
#include "fileio.h"
#include "job.h"
#include "metrics.h"
#include "points.h"
#include "run.h"

static const char usage[] =
    "usage: worker JOB.yaml [JOB.yaml ...]     render each job file, in order\n"
    "       worker diff A.png B.png [--max-rmse X]  error of B against reference A\n"
    "       worker points SAMPLER THRESHOLD [--seed S] [--svg F]  print a point set as CSV\n"
    "       worker --help | --version\n"
    "options: --out DIR (default ./out)  --processes N (overrides the job)  --quiet\n";

static const char help[] =
    "worker: a batch render worker around a Monte Carlo path tracer for studying samplers.\n"
    "\n"
    "Each job file (YAML) names a scene, a pixel sampler (uniform | jitter | random | poisson)\n"
    "and its threshold (the minimum spacing in a 100x100 domain: 1 gives 10000 samples per\n"
    "pixel for uniform/jitter/random, about 6400 for poisson). Rows are split over forked\n"
    "processes; the image (PNG or PPM) and a JSON stats sidecar land in OUT/<job name>/.\n"
    "\n"
    "exit status: 0 all jobs done, 1 a job failed while rendering, 2 bad usage or bad input.\n";

static void print_err(const struct err *e)
{
    char buf[2048];
    err_format(e, buf, sizeof buf);
    fprintf(stderr, "%s\n", buf);
}

static int parse_double_arg(const char *s, double *out)
{
    char *end;
    *out = strtod(s, &end);
    return *s && !*end ? 0 : -1;
}

static int diff_main(int argc, char **argv)
{
    const char *files[2] = {0};
    int nfiles = 0;
    double max_rmse = -1;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--max-rmse")) {
            if (i + 1 >= argc || parse_double_arg(argv[++i], &max_rmse) < 0 || max_rmse < 0) {
                fprintf(stderr, "worker diff: --max-rmse needs a number >= 0\n");
                return 2;
            }
        } else if (argv[i][0] == '-' && argv[i][1]) {
            fprintf(stderr, "worker diff: unknown option %s\n%s", argv[i], usage);
            return 2;
        } else if (nfiles < 2) {
            files[nfiles++] = argv[i];
        } else {
            fprintf(stderr, "worker diff: expected two images, got a third: %s\n", argv[i]);
            return 2;
        }
    }
    if (nfiles != 2) {
        fprintf(stderr, "worker diff: expected two images (reference, then image)\n%s", usage);
        return 2;
    }
    struct rgb8 a = {0}, b = {0};
    struct metrics m;
    struct err e;
    int rc = 2;
    if (imgio_read(files[0], &a, &e) == 0 && imgio_read(files[1], &b, &e) == 0) {
        if (metrics_compare(&a, &b, &m, &e) == 0) {
            printf("mse %.9g\nrmse %.9g\nrelmse %.9g\npsnr %.4f\n", m.mse, m.rmse, m.relmse, m.psnr);
            rc = 0;
            if (max_rmse >= 0 && m.rmse > max_rmse) {
                fprintf(stderr, "worker diff: rmse %.6g is over --max-rmse %g\n", m.rmse, max_rmse);
                rc = 1;
            }
        } else {
            snprintf(e.file, sizeof e.file, "%s", files[1]);
        }
    }
    if (rc == 2)
        print_err(&e);
    rgb8_free(&a);
    rgb8_free(&b);
    return rc;
}

int main(int argc, char **argv)
{
    /* A file-size limit must fail our write() with EFBIG (reported, temp file removed), not
       kill the process half-way through an output. */
    signal(SIGXFSZ, SIG_IGN);
    if (argc >= 2 && !strcmp(argv[1], "points"))
        return points_main(argc - 1, argv + 1);
    if (argc >= 2 && !strcmp(argv[1], "diff"))
        return diff_main(argc - 1, argv + 1);
    struct run_opts o = {"out", 0, 0, isatty(2)};
    const char **jobs = calloc((size_t)argc, sizeof *jobs);
    int njobs = 0;
    if (!jobs)
        return 2;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            printf("%s\n%s", help, usage);
            free(jobs);
            return 0;
        } else if (!strcmp(a, "--version")) {
            printf("worker %s\n", WORKER_VERSION);
            free(jobs);
            return 0;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            o.quiet = 1;
        } else if (!strcmp(a, "--out") || !strcmp(a, "--processes")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "worker: %s needs a value\n%s", a, usage);
                free(jobs);
                return 2;
            }
            const char *v = argv[++i];
            if (a[2] == 'o') {
                o.out_dir = v;
            } else {
                char *end;
                long n = strtol(v, &end, 10);
                if (!*v || *end || n < 1 || n > FARM_MAX_PROCESSES) {
                    fprintf(stderr, "worker: --processes must be a whole number in [1, %d], got \"%s\"\n",
                            FARM_MAX_PROCESSES, v);
                    free(jobs);
                    return 2;
                }
                o.processes = (int)n;
            }
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "worker: unknown option %s\n%s", a, usage);
            free(jobs);
            return 2;
        } else {
            jobs[njobs++] = a;
        }
    }
    if (njobs == 0) {
        fprintf(stderr, "worker: no job file given\n%s", usage);
        free(jobs);
        return 2;
    }
    int worst = 0;
    for (int i = 0; i < njobs; i++) {
        struct job j;
        struct err e;
        struct run_result rr;
        if (compare_is_compare_job(jobs[i])) {
            int rc = compare_main(jobs[i], &o);
            worst = rc > worst ? rc : worst;
            continue;
        }
        if (job_load(jobs[i], &j, &e) < 0) {
            print_err(&e);
            worst = 2;
            continue;
        }
        int rc = run_job(&j, &o, &rr, &e);
        if (rc != 0) {
            if (rc == 1) { /* a render failure names the job; bad input names its file */
                char why[sizeof e.msg];
                snprintf(why, sizeof why, "%s", e.msg);
                snprintf(e.msg, sizeof e.msg, "%s: %s; nothing written", j.name, why);
            }
            print_err(&e);
            worst = rc > worst ? rc : worst;
            continue;
        }
        const struct render_stats *t = &rr.farm.total;
        fprintf(stderr, "%s: %dx%d %s t=%g (%.0f spp mean), %d processes, %.2f s -> %s\n", j.name, rr.width,
                rr.height, sampler_kind_name(j.sampler), j.threshold,
                t->pixels ? (double)t->samples / t->pixels : 0.0, rr.farm.processes, rr.farm.wall_s,
                rr.image_path);
    }
    free(jobs);
    return worst;
}
