/* dryrun: a job's, compare job's or suite's estimate, written nowhere but stdout. */
#include "dryrun.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "base/clock.h"
#include "cli.h"
#include "job/job_estimate.h"
#include "job/jobfile.h"
#include "study/run/compare_ref.h"
#include "study/run/study_fan.h"
#include "study/run/study_scenes.h"
#include "study/judge/verdict.h"

/* The cost model's measuring budget in CPU seconds (cost_model.h: each pilot takes a path at
   least, each set timing a set): a plain job's, and a compare job's or suite's in all. */
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

static double mb(double bytes)
{
    return bytes / (1 << 20);
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

/* cpu_s, and its wall time spread over `processes` processes on at most this machine's cores. */
static void print_cpu(double cpu_s, int processes, const char *how)
{
    char a[32], b[32], cores[48] = "";
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    const int p = processes < 1 ? 1 : processes;
    if (n > 0 && n < processes)
        snprintf(cores, sizeof cores, " (%ld cores here)", n);
    printf("  CPU time  about %s%s; wall about %s on %d process%s%s\n", duration(cpu_s, a, sizeof a), how,
           duration(cpu_s / (double)(n > 0 && n < p ? n : p), b, sizeof b), processes,
           processes == 1 ? "" : "es", cores);
}

/* Where the estimate's CPU time goes: tracing and each kind of point set. */
static void print_parts(const struct cost_estimate *c)
{
    char a[32], b[32], n[32];
    printf("  cost      tracing %s (%.3g ns per sample); pixel sets %s", duration(c->trace_s, a, sizeof a),
           c->ns_per_sample, duration(c->pixel_sets_s, b, sizeof b));
    if (c->light_sets > 0)
        printf("; %s light sets %s", count(c->light_sets, n, sizeof n),
               duration(c->light_sets_s, a, sizeof a));
    if (c->padded_sets > 0)
        printf("; %s padded sets %s", count(c->padded_sets, n, sizeof n),
               duration(c->padded_sets_s, a, sizeof a));
    printf("%s\n", c->sets_scaled ? " (sets too large to draw here: timed smaller, scaled)" : "");
}

/* The CPU seconds this dry run took, all of it (the measuring and the rest). */
static void print_took(void)
{
    printf("  dry run   took %.3g s of CPU\n", clock_s(CLOCK_PROCESS_CPUTIME_ID));
}

static int plain(const struct jobfile *f, const struct run_opts *o)
{
    const struct job *j = &f->job;
    struct job_estimate est;
    struct scene_file sf = {0};
    struct err e = {0};
    struct cost_model *m = cost_model_new(DRYRUN_JOB_BUDGET_S);
    /* the scene as jobfile_open read it: built here, not read again */
    int rc = !m ? (err_set(&e, j->path, 0, 0, "out of memory"), 2)
             : scene_load_src(&f->scene, &sf, &e) < 0 || job_estimate(j, &sf, o->processes, m, &est, &e) < 0
                 ? 2
                 : 0;
    scene_file_free(&sf);
    cost_model_free(m);
    if (rc) {
        cli_print_err(&e);
        return 2;
    }
    const struct cost_estimate *c = &est.cost;
    char light[96];
    printf("%s: dry run: nothing rendered, nothing written\n", j->name);
    printf("  image     %dx%d, %s t=%g, %s -> %s/%s/%s\n", est.width, est.height,
           sampler_kind_name(j->spec.pixel.kind), j->spec.pixel.threshold,
           job_light_text(j, light, sizeof light), o->out_dir, j->name, j->output);
    char num[32];
    printf("  samples   %s (%.4g per pixel)\n", count(est.samples, num, sizeof num), est.spp_mean);
    print_memory(&est, "about");
    char how[160], cut[64] = "";
    if (c->pilot_traced < c->pilot_samples) /* a pixel too costly for the pilot's time */
        snprintf(cut, sizeof cut, ", %.0f of %s %.0f samples traced", c->pilot_traced,
                 c->pilot_pixels == 1 ? "its" : "their", c->pilot_samples);
    snprintf(how, sizeof how, " (%.3g ns per sample, from a pilot of %d pixel%s%s)", c->ns_per_sample,
             c->pilot_pixels, c->pilot_pixels == 1 ? "" : "s", cut);
    print_cpu(est.cpu_s, est.processes, how);
    print_parts(c);
    print_took();
    return 0;
}

/* What one compare job's estimates add up to. */
struct study_sum {
    double samples, cpu_s, ref_cpu_s, spp_lo, spp_hi;
    struct job_estimate largest; /* of the most memory */
    int processes;
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
                           struct cost_model *m, const struct run_opts *o, struct study_sum *sum,
                           struct err *e)
{
    const struct compare_scene *cs = &c->scenes[s];
    struct job_estimate est, half;
    struct job hj;
    /* as rendered: two independent halves, each at the thresholds times sqrt 2 */
    compare_ref_half_job(cs, 0, &hj);
    if (job_estimate(&hj, sf, o->processes, m, &half, e) < 0)
        return -1;
    est = half;
    est.samples = 2 * half.samples;
    est.spp_mean = 2 * half.spp_mean;
    est.cpu_s = 2 * half.cpu_s;
    char a[32], num[32], light[96];
    printf("  reference %s: %dx%d %s t=%g, %s: %s samples (%.4g per pixel: two halves at t=%g), CPU about %s "
           "(unless cached)\n",
           cs->name, est.width, est.height, sampler_kind_name(cs->ref_job.spec.pixel.kind),
           cs->ref_job.spec.pixel.threshold, job_light_text(&cs->ref_job, light, sizeof light),
           count(est.samples, num, sizeof num), est.spp_mean, hj.spec.pixel.threshold,
           duration(est.cpu_s, a, sizeof a));
    if (est.spp_mean < VERDICT_REF_FACTOR * densest)
        printf("  warning: %s: the reference would have %.0f samples per pixel, fewer than %dx the densest "
               "point's %.0f: its own noise would be a large part of the error measured there; give the "
               "reference a smaller threshold\n",
               cs->name, est.spp_mean, VERDICT_REF_FACTOR, densest);
    sum->ref_cpu_s += est.cpu_s;
    return 0;
}

/* Sweep points of scene s and variant v whose images get the same samples per pixel (spp, by point;
   thresholds 100 and 80 both give one): warned once per variant, naming the first such pair. */
static void warn_same_points(const struct compare *c, int s, int v, const double *spp)
{
    for (int p = 0; p < c->n_points; p++)
        for (int q = p + 1; q < c->n_points; q++)
            if (spp[p] > 0 && fabs(spp[p] - spp[q]) <= 1e-9 * spp[p]) {
                printf("  warning: %s, %s: sweep points %s and %s both give %.4g sample%s per pixel: they "
                       "measure one thing twice; pick thresholds further apart\n",
                       c->scenes[s].name, c->variants[v], c->points[p], c->points[q], spp[p],
                       spp[p] == 1 ? "" : "s");
                return;
            }
}

/* What the dry run can tell before rendering that would make the study say less than asked. */
static void warn_study(const struct compare *c, const double *spp)
{
    if (c->n_seeds < 2)
        printf("  warning: one seed: no spread across seeds to judge a difference by, so the verdict ranks "
               "nothing; give seeds: [1, 2, ...] (8 or more to separate close variants)\n");
    for (int s = 0; s < c->n_scenes; s++)
        for (int v = 0; v < c->n_variants; v++)
            warn_same_points(c, s, v, spp + ((size_t)s * c->n_variants + v) * c->n_points);
}

/* Estimate every image of c (once per seedless combination: seeds cost alike) and its references
   by the cost model m (its pilots and set timings shared between combinations of equal settings). */
static int study(const struct compare *c, const struct study_scenes *ds, struct cost_model *m,
                 const struct run_opts *o, struct study_sum *sum, struct err *e)
{
    int rc = -1;
    double *densest = calloc((size_t)c->n_scenes, sizeof *densest);
    double *spp = calloc((size_t)c->n_scenes * c->n_variants * c->n_points, sizeof *spp);
    *sum = (struct study_sum){.spp_lo = 1e300};
    if (!densest || !spp) {
        err_set(e, c->path, 0, 0, "out of memory");
        goto done;
    }
    for (int i = 0; i < c->n_items; i++) {
        const struct compare_item *it = &c->items[i];
        struct job_estimate est;
        if (it->seed != 0)
            continue;
        if (job_estimate(&it->job, study_scenes_of(ds, &c->scenes[it->scene]), o->processes, m, &est, e) < 0)
            goto done;
        sum->samples += est.samples * c->n_seeds;
        sum->cpu_s += est.cpu_s * c->n_seeds;
        sum->spp_lo = est.spp_mean < sum->spp_lo ? est.spp_mean : sum->spp_lo;
        sum->spp_hi = est.spp_mean > sum->spp_hi ? est.spp_mean : sum->spp_hi;
        densest[it->scene] = est.spp_mean > densest[it->scene] ? est.spp_mean : densest[it->scene];
        spp[((size_t)it->scene * c->n_variants + it->variant) * c->n_points + it->point] = est.spp_mean;
        if (job_estimate_memory(&est) > job_estimate_memory(&sum->largest))
            sum->largest = est;
        sum->processes = est.processes;
    }
    print_study(c, sum);
    warn_study(c, spp);
    for (int s = 0; s < c->n_scenes; s++)
        if (c->scenes[s].ref_kind == COMPARE_REF_SETTINGS &&
            study_reference(c, s, study_scenes_of(ds, &c->scenes[s]), densest[s], m, o, sum, e) < 0)
            goto done;
    rc = 0;
done:
    free(densest);
    free(spp);
    return rc;
}

static int compare_job(const struct jobfile *f, const struct run_opts *o)
{
    struct err e = {0};
    struct study_fan fan = {0};
    if (study_fan_load(f, &fan, &e) < 0) {
        cli_print_err(&e);
        return 2;
    }
    struct compare *const *studies = fan.s ? fan.s->studies : &fan.c;
    int n = study_fan_studies(&fan), rc = 0;
    struct cost_model *m = cost_model_new(DRYRUN_STUDY_BUDGET_S);
    struct study_scenes ds = {0};
    double cpu_s = 0, ref_cpu_s = 0;
    int processes = 1;
    printf("%s: dry run: nothing rendered, nothing written\n", study_fan_name(&fan));
    if (!m)
        err_set(&e, f->path, 0, 0, "out of memory");
    if (!m || study_scenes_prepare(studies, n, &ds, m, &e) < 0) {
        cli_print_err(&e);
        rc = 2;
    }
    for (int i = 0; i < n && rc == 0; i++) {
        struct study_sum sum;
        if (fan.s)
            printf(" study %s\n", studies[i]->name);
        if (study(studies[i], &ds, m, o, &sum, &e) < 0) {
            cli_print_err(&e);
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
        print_took();
    }
    study_scenes_free(&ds);
    cost_model_free(m);
    study_fan_free(&fan);
    return rc;
}

int dryrun_main(const char *path, const struct run_opts *o)
{
    struct jobfile f;
    struct err e = {0};
    int rc = 2;
    if (jobfile_open(&f, path, path, &e) < 0)
        cli_print_err(&e);
    else
        rc = f.kind == JOBFILE_PLAIN ? plain(&f, o) : compare_job(&f, o);
    jobfile_close(&f);
    return rc;
}
