/* dryrun: a job's, compare job's or suite's estimate, written nowhere but stdout. */
#include "dryrun.h"

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "job/job_estimate.h"
#include "job/jobfile.h"
#include "study/load/compare_load.h"
#include "study/load/compare_suite_load.h"
#include "study/run/compare_ref.h"
#include "study/judge/verdict.h"

/* One plain job's pilot, and what all of a compare job's pilots share (each takes a pixel at
   least), in CPU seconds. */
#define DRYRUN_JOB_BUDGET_S 0.5
#define DRYRUN_STUDY_BUDGET_S 3.0

/* Seconds as "850 ms", "42 s", "12 min", "3.4 h". */
static const char *duration(double s, char *buf, size_t n)
{
    if (s < 1)
        snprintf(buf, n, "%.0f ms", s * 1e3);
    else if (s < 120)
        snprintf(buf, n, "%.3g s", s);
    else if (s < 7200)
        snprintf(buf, n, "%.3g min", s / 60);
    else
        snprintf(buf, n, "%.3g h", s / 3600);
    return buf;
}

/* A count in full below ten million, else with 4 significant digits. */
static const char *count(double v, char *buf, size_t n)
{
    snprintf(buf, n, v < 1e7 ? "%.0f" : "%.4g", v);
    return buf;
}

static void err_print_e(const struct err *e)
{
    char buf[2048];
    err_format(e, buf, sizeof buf);
    fprintf(stderr, "%s\n", buf);
}

static double mb(double bytes)
{
    return bytes / (1 << 20);
}

/* The wall time of cpu_s spread over `processes` processes, on at most this machine's cores. */
static double wall_of(double cpu_s, int processes)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    int p = processes < 1 ? 1 : processes;
    return cpu_s / (double)(cores > 0 && cores < p ? cores : p);
}

static void print_memory(const struct job_estimate *est, const char *what)
{
    char tex[64] = "";
    if (est->texture_bytes > 0)
        snprintf(tex, sizeof tex, " + textures %.3g MB, shared", mb(est->texture_bytes));
    printf("  memory    %s %.3g MB (framebuffer %.3g MB%s + %d process%s x %.3g MB)\n", what,
           mb(job_estimate_memory(est)), mb(est->framebuffer_bytes), tex, est->processes,
           est->processes == 1 ? "" : "es", mb(est->process_bytes));
}

static void print_cpu(double cpu_s, int processes, const char *how)
{
    char a[32], b[32], cores[48] = "";
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    if (n > 0 && n < processes)
        snprintf(cores, sizeof cores, " (%ld cores here)", n);
    printf("  CPU time  about %s%s; wall about %s on %d process%s%s\n", duration(cpu_s, a, sizeof a), how,
           duration(wall_of(cpu_s, processes), b, sizeof b), processes, processes == 1 ? "" : "es", cores);
}

static int plain(const struct jobfile *f, const struct run_opts *o)
{
    const struct job *jp = &f->job;
    struct job_estimate est;
    struct scene_file sf = {0};
    struct err e = {0};
    /* the scene as jobfile_open read it: built here, not read again */
    int rc = scene_load_src(&f->scene, &sf, &e) < 0 ||
                     job_estimate(jp, &sf, o->processes, DRYRUN_JOB_BUDGET_S, &est, &e) < 0
                 ? 2
                 : 0;
    scene_file_free(&sf);
    if (rc) {
        err_print_e(&e);
        return 2;
    }
    const struct job j = *jp;
    printf("%s: dry run: nothing rendered, nothing written\n", j.name);
    printf("  image     %dx%d, %s t=%g, light %s t=%g -> %s/%s/%s\n", est.width, est.height,
           sampler_kind_name(j.sampler), j.threshold, sampler_kind_name(j.light_sampler), j.light_threshold,
           o->out_dir, j.name, j.output);
    char num[32];
    printf("  samples   %s (%.4g per pixel)\n", count(est.samples, num, sizeof num), est.spp_mean);
    print_memory(&est, "about");
    char how[160], cut[64] = "";
    if (est.pilot_traced < est.pilot_samples) /* a pixel too costly for the pilot's time */
        snprintf(cut, sizeof cut, ", %.0f of %s %.0f samples traced", est.pilot_traced,
                 est.pilot_pixels == 1 ? "its" : "their", est.pilot_samples);
    snprintf(how, sizeof how, " (%.3g ns per sample, from a pilot of %d pixel%s%s)", est.ns_per_sample,
             est.pilot_pixels, est.pilot_pixels == 1 ? "" : "s", cut);
    print_cpu(est.cpu_s, est.processes, how);
    return 0;
}

/* What one compare job's estimates add up to. */
struct study_sum {
    double samples, cpu_s, ref_cpu_s, spp_lo, spp_hi;
    struct job_estimate largest; /* of the most memory */
    int processes, refs;
};

static void print_study(const struct compare *c, const struct study_sum *sum)
{
    char a[32], num[32];
    printf(
        "  images    %d (%d scene%s x %d variant%s x %d point%s x %d seed%s): %s samples (%.4g to %.4g per "
        "pixel), CPU about %s\n",
        c->n_items, c->n_scenes, c->n_scenes == 1 ? "" : "s", c->n_variants, c->n_variants == 1 ? "" : "s",
        c->n_points, c->n_points == 1 ? "" : "s", c->n_seeds, c->n_seeds == 1 ? "" : "s",
        count(sum->samples, num, sizeof num), sum->spp_lo, sum->spp_hi, duration(sum->cpu_s, a, sizeof a));
    print_memory(&sum->largest, "at most");
}

/* The reference of scene s (given as settings): its estimate, and the guard the verdict applies
   once it is rendered (verdict_say_warnings), known now. */
static int study_reference(const struct compare *c, int s, const struct scene_file *sf, double densest,
                           double budget, const struct run_opts *o, struct study_sum *sum, struct err *e)
{
    const struct compare_scene *cs = &c->scenes[s];
    struct job_estimate est, half;
    struct job hj;
    /* as rendered: two independent halves, each at the thresholds times sqrt 2 */
    compare_ref_half_job(cs, 0, &hj);
    if (job_estimate(&hj, sf, o->processes, budget, &half, e) < 0)
        return -1;
    est = half;
    est.samples = 2 * half.samples;
    est.spp_mean = 2 * half.spp_mean;
    est.cpu_s = 2 * half.cpu_s;
    char a[32], num[32];
    printf("  reference %s: %dx%d %s t=%g: %s samples (%.4g per pixel: two halves at t=%g), CPU about %s "
           "(unless cached)\n",
           cs->name, est.width, est.height, sampler_kind_name(cs->ref_job.sampler), cs->ref_job.threshold,
           count(est.samples, num, sizeof num), est.spp_mean, hj.threshold, duration(est.cpu_s, a, sizeof a));
    if (est.spp_mean < VERDICT_REF_FACTOR * densest)
        printf("  warning: %s: the reference would have %.0f samples per pixel, fewer than %dx the densest "
               "point's %.0f: its own noise would be a large part of the error measured there; give the "
               "reference a smaller threshold\n",
               cs->name, est.spp_mean, VERDICT_REF_FACTOR, densest);
    sum->ref_cpu_s += est.cpu_s;
    sum->refs++;
    return 0;
}

/* Estimate every image of c (once per seedless combination: seeds cost alike) and its references. */
static int study(const struct compare *c, const struct run_opts *o, struct study_sum *sum, struct err *e)
{
    int rc = -1, combos = c->n_items / (c->n_seeds > 0 ? c->n_seeds : 1);
    double budget = DRYRUN_STUDY_BUDGET_S / (combos + c->n_scenes);
    double *densest = calloc((size_t)c->n_scenes, sizeof *densest);
    struct scene_file *sf = calloc((size_t)c->n_scenes, sizeof *sf);
    *sum = (struct study_sum){.spp_lo = 1e300};
    for (int s = 0; sf && s < c->n_scenes; s++)
        if (scene_load_src(&c->scenes[s].input->src, &sf[s], e) < 0) /* as the study read it */
            goto done;
    for (int i = 0; sf && densest && i < c->n_items; i++) {
        const struct compare_item *it = &c->items[i];
        struct job_estimate est;
        if (it->seed != 0)
            continue;
        if (job_estimate(&it->job, &sf[it->scene], o->processes, budget, &est, e) < 0)
            goto done;
        sum->samples += est.samples * c->n_seeds;
        sum->cpu_s += est.cpu_s * c->n_seeds;
        sum->spp_lo = est.spp_mean < sum->spp_lo ? est.spp_mean : sum->spp_lo;
        sum->spp_hi = est.spp_mean > sum->spp_hi ? est.spp_mean : sum->spp_hi;
        densest[it->scene] = est.spp_mean > densest[it->scene] ? est.spp_mean : densest[it->scene];
        if (job_estimate_memory(&est) > job_estimate_memory(&sum->largest))
            sum->largest = est;
        sum->processes = est.processes;
    }
    if (sf && densest)
        print_study(c, sum);
    for (int s = 0; sf && densest && s < c->n_scenes; s++)
        if (c->scenes[s].ref_kind == COMPARE_REF_SETTINGS &&
            study_reference(c, s, &sf[s], densest[s], budget, o, sum, e) < 0)
            goto done;
    rc = sf && densest ? 0 : err_set(e, c->path, 0, 0, "out of memory");
done:
    for (int s = 0; sf && s < c->n_scenes; s++)
        scene_file_free(&sf[s]);
    free(sf);
    free(densest);
    return rc;
}

static int compare_job(const struct jobfile *f, const struct run_opts *o)
{
    struct err e = {0};
    struct compare_suite *suite = NULL;
    struct compare *one = NULL;
    if (f->kind == JOBFILE_SUITE ? !(suite = compare_suite_load_doc(&f->doc, f->path, &e))
                                 : !(one = compare_load_doc(&f->doc, f->path, &e))) {
        err_print_e(&e);
        return 2;
    }
    struct compare *const *studies = suite ? suite->studies : &one;
    int n = suite ? suite->n_studies : 1, rc = 0;
    double cpu_s = 0, ref_cpu_s = 0;
    int processes = 1;
    printf("%s: dry run: nothing rendered, nothing written\n", suite ? suite->name : one->name);
    for (int i = 0; i < n && rc == 0; i++) {
        struct study_sum sum;
        if (suite)
            printf(" study %s\n", studies[i]->name);
        if (study(studies[i], o, &sum, &e) < 0) {
            err_print_e(&e);
            rc = 2;
            break;
        }
        cpu_s += sum.cpu_s + sum.ref_cpu_s;
        ref_cpu_s += sum.ref_cpu_s;
        processes = sum.processes > processes ? sum.processes : processes;
    }
    if (rc == 0) {
        char how[96], a[32];
        snprintf(how, sizeof how, " in all (references %s of it, unless cached), from pilots of a few pixels",
                 duration(ref_cpu_s, a, sizeof a));
        print_cpu(cpu_s, processes, how);
    }
    compare_suite_free(suite);
    compare_free(one);
    return rc;
}

int dryrun_main(const char *path, const struct run_opts *o)
{
    struct jobfile f;
    struct err e = {0};
    int rc = 2;
    if (jobfile_open(&f, path, path, &e) < 0)
        err_print_e(&e);
    else
        rc = f.kind == JOBFILE_PLAIN ? plain(&f, o) : compare_job(&f, o);
    jobfile_close(&f);
    return rc;
}
