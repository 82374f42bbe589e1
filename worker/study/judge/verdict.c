/* verdict: rankings with ties, slopes, failure modes and guards from one scene's figures. */
#include "verdict.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "verdict_center.h"
#include "verdict_look.h"
#include "verdict_rank.h"
#include "verdict_say.h"
#include "verdict_spectrum.h"
#include "verdict_time.h"

/* Least-squares line of log y against log x over seed k's points of v: y = exp(a + b log x). */
static int fit(const struct verdict_figures *f, const double *x, int v, int k, double *a, double *b)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int m = 0;
    for (int p = 0; p < f->n_points; p++) {
        double xi = x[verdict_at(f, v, p, k)], yi = verdict_rel(f, verdict_at(f, v, p, k));
        if (!(xi > 0 && yi > 0 && isfinite(xi) && isfinite(yi)))
            continue;
        double lx = log(xi), ly = log(yi);
        sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
        m++;
    }
    double den = m * sxx - sx * sx;
    if (m < 2 || !(den > 1e-12))
        return -1;
    *b = (m * sxy - sx * sy) / den;
    *a = (sy - *b * sx) / m;
    return 0;
}

/* A variant whose cheapest point costs this many times the common point or more cannot be had
   there: it is ranked behind every variant that can. Less is one seed's samples or timing a
   little off the mean the others are read at. */
#define VERDICT_BEYOND 1.25

/* A measured point: its x (spp or time) and its relMSE y. */
struct xy {
    double x, y;
};

/* The seed's measured point of v nearest to `at` on one side (below: x <= at, else x >= at),
   skipping x == skip, into o; 0 when there is none. */
static int nearest(const struct verdict_figures *f, const double *x, int v, int k, double at, int below,
                   double skip, struct xy *o)
{
    int found = 0;
    for (int p = 0; p < f->n_points; p++) {
        double xi = x[verdict_at(f, v, p, k)], yi = verdict_rel(f, verdict_at(f, v, p, k));
        if (!(xi > 0 && yi > 0 && isfinite(xi) && isfinite(yi)) || xi == skip)
            continue;
        if (fabs(xi - at) <= 1e-9 * at) /* the point itself (at is a mean over seeds: rounding) */
            xi = at;
        if ((below ? xi <= at : xi >= at) && (!found || fabs(xi - at) < fabs(o->x - at)))
            o->x = xi, o->y = yi, found = 1;
    }
    return found;
}

/* Seed k's relMSE of variant v at x = at: linear in log-log between the measured points around
   it, or along the segment of the two nearest when it lies just beyond them. NAN: none measured. */
static double value_at(const struct verdict_figures *f, const double *x, int v, int k, double at)
{
    struct xy a, b;
    int lo = nearest(f, x, v, k, at, 1, NAN, &a), hi = nearest(f, x, v, k, at, 0, NAN, &b);
    if (lo && hi && a.x == b.x)
        return a.y;
    if (!lo && !hi)
        return NAN;
    if (!lo || !hi) { /* extend the end segment: the nearest point and the next on its side */
        if (!lo)
            a = b;
        if (!nearest(f, x, v, k, at, lo, a.x, &b))
            return a.y;
    }
    double t = log(at / a.x) / log(b.x / a.x);
    return exp(log(a.y) + t * (log(b.y) - log(a.y)));
}

/* Seed k's relMSE into e, and its log into logs[k] (NAN when not positive). */
static void entry_add(struct verdict_entry *e, double *logs, int k, double y)
{
    verdict_entry_add(e, y, 1);
    logs[k] = y > 0 && isfinite(y) ? log(y) : NAN;
}

/* Rank every variant by relMSE at the x that every variant reached: the smallest of their
   densest points' means (the cheapest densest point, for CPU time). A variant whose cheapest
   point lies far beyond it is unreached, shown with its cheapest point's figures. logs: room for
   n_seeds doubles. */
static void rank_at(const struct verdict_figures *f, const double *x, double *logs, struct verdict_ranking *r)
{
    double at = INFINITY;
    for (int v = 0; v < f->n_variants; v++) {
        double most = 0;
        for (int p = 0; p < f->n_points; p++)
            most = fmax(most, verdict_mean(f, x, v, p));
        at = fmin(at, most);
    }
    r->at = at;
    r->n = f->n_variants;
    for (int v = 0; v < f->n_variants; v++) {
        struct verdict_entry *e = &r->e[v];
        verdict_entry_start(e, v);
        int cheapest = 0;
        for (int p = 1; p < f->n_points; p++)
            if (verdict_mean(f, x, v, p) < verdict_mean(f, x, v, cheapest))
                cheapest = p;
        e->unreached = verdict_mean(f, x, v, cheapest) > at * VERDICT_BEYOND;
        for (int k = 0; k < f->n_seeds; k++) /* unreached: its cheapest point's figures */
            entry_add(e, logs, k,
                      e->unreached ? verdict_rel(f, verdict_at(f, v, cheapest, k))
                                   : value_at(f, x, v, k, at));
        verdict_entry_end(e, 1);
        if (f->rank_by == VERDICT_RANK_MEDIAN)
            verdict_entry_logs(e, logs, f->n_seeds, f->rank_by);
    }
    verdict_rank(r);
}

int verdict_samples_vary(double lo, double hi)
{
    return hi > lo * VERDICT_SAMPLES_VARY;
}

/* Whether v's points change its samples per pixel (a slope needs them to). */
static int samples_vary(const struct verdict_figures *f, int v)
{
    double lo = INFINITY, hi = 0;
    for (int p = 0; p < f->n_points; p++)
        lo = fmin(lo, verdict_mean(f, f->spp, v, p)), hi = fmax(hi, verdict_mean(f, f->spp, v, p));
    return verdict_samples_vary(lo, hi);
}

/* Each variant's slope of log relMSE against log samples per pixel, fitted per seed. */
static void rank_slopes(const struct verdict_figures *f, struct verdict_ranking *r)
{
    r->at = NAN;
    r->n = 0;
    for (int v = 0; v < f->n_variants; v++) {
        if (!samples_vary(f, v))
            continue;
        struct verdict_entry *e = &r->e[r->n];
        verdict_entry_start(e, v);
        double a, b;
        for (int k = 0; k < f->n_seeds; k++)
            if (fit(f, f->spp, v, k, &a, &b) == 0)
                verdict_entry_add(e, b, 0);
        verdict_entry_end(e, 0);
        r->n += e->n > 0;
    }
    verdict_rank(r);
}

/* The points of v in order of mean samples per pixel. */
static void by_samples(const struct verdict_figures *f, int v, int *order)
{
    for (int p = 0; p < f->n_points; p++)
        order[p] = p;
    for (int i = 1; i < f->n_points; i++)
        for (int j = i;
             j > 0 && verdict_mean(f, f->spp, v, order[j]) < verdict_mean(f, f->spp, v, order[j - 1]); j--) {
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
}

/* The share of each (v, p)'s error that repeats in every seed, and the part of it a bias in mean
   radiance makes: averaging n seeds' images divides noise by n and leaves structure, so with the
   reference's own relMSE taken out of both, share = (n rel_of_mean / mean_rel - 1) / (n - 1). */
static void repeat_shares(const struct verdict_figures *f, struct verdict_scene *out)
{
    int n = f->n_seeds, np = f->n_points;
    double ref = f->ref.relmse > 0 ? f->ref.relmse : 0;
    for (int v = 0; v < f->n_variants; v++)
        for (int p = 0; p < np; p++) {
            double rom = f->rel_of_mean ? f->rel_of_mean[v * np + p] - ref : NAN;
            double mr = verdict_mean(f, f->relmse, v, p) - ref, share = NAN, bias = NAN;
            if (n > 1 && isfinite(rom) && mr > 0) {
                share = fmin(1, fmax(0, (n * rom / mr - 1) / (n - 1)));
                if (f->bias_rel && isfinite(f->bias_rel[v * np + p]))
                    bias = fmin(share, fmax(0, f->bias_rel[v * np + p] / mr));
            }
            out->repeat[v * np + p] = share, out->repeat_bias[v * np + p] = bias;
        }
}

/* A bias: v's seeds' mean radiance at the point where it is most standard errors (the seeds'
   spread and the reference's noise) off the reference's, when that is over VERDICT_BIAS_SE. */
static void bias_of(const struct verdict_figures *f, int v, struct verdict_scene *out)
{
    if (!f->radiance || !(f->ref.radiance > 0) || f->n_seeds < VERDICT_BIAS_SEEDS)
        return;
    double ref_se = isfinite(f->ref.radiance_se) ? f->ref.radiance_se : 0, worst = 0, pct = 0;
    int at = -1;
    for (int p = 0; p < f->n_points; p++) {
        struct verdict_entry e;
        verdict_entry_start(&e, v);
        for (int k = 0; k < f->n_seeds; k++)
            verdict_entry_add(&e, f->radiance[verdict_at(f, v, p, k)], 0);
        verdict_entry_end(&e, 0);
        double se = sqrt(e.se * e.se + ref_se * ref_se), z = (e.mean - f->ref.radiance) / se;
        if (e.n > 1 && se > 0 && fabs(z) > fabs(worst))
            worst = z, at = p, pct = 100 * (e.mean / f->ref.radiance - 1);
    }
    if (fabs(worst) > VERDICT_BIAS_SE)
        verdict_say_failure(f, out, VERDICT_BIASED, v, at, pct, worst);
}

/* Fireflies: the point where v's seeds' relMSE span the largest factor, flagged when over
   VERDICT_HEAVY_RATIO. Returns whether it was. */
static int heavy_tailed(const struct verdict_figures *f, int v, struct verdict_scene *out)
{
    int n = f->n_seeds, at = -1;
    double most = 0, share = NAN;
    for (int p = 0; p < f->n_points && n >= VERDICT_HEAVY_SEEDS; p++) {
        double sum = 0, lo = INFINITY, hi = 0;
        int m = 0;
        for (int k = 0; k < n; k++) {
            double r = f->relmse[verdict_at(f, v, p, k)];
            if (isfinite(r) && r >= 0)
                lo = fmin(lo, r), hi = fmax(hi, r), sum += r, m++;
        }
        if (m >= VERDICT_HEAVY_SEEDS && lo > 0 && hi / lo > most)
            most = hi / lo, at = p, share = hi / sum;
    }
    if (!(most > VERDICT_HEAVY_RATIO))
        return 0;
    verdict_say_failure(f, out, VERDICT_HEAVY_TAILED, v, at, most, share);
    return 1;
}

/* The failure modes of variant v: structured error, fireflies, error that stops falling,
   non-finite samples, a sampler's CPU share and a bias, each at the point where it shows most;
   fireflies suppress the last's and the stall's tests (they read a mean that means nothing). */
static void failures_of(const struct verdict_figures *f, int v, int *order, struct verdict_scene *out)
{
    int at = -1;
    double most = 0;
    for (int p = 0; p < f->n_points; p++) {
        double s = out->repeat[v * f->n_points + p];
        if (isfinite(s) && s > most)
            most = s, at = p;
    }
    if (f->n_seeds > 1 && most > VERDICT_STRUCTURED_SHARE)
        verdict_say_failure(f, out, VERDICT_STRUCTURED, v, at, most, out->repeat_bias[v * f->n_points + at]);
    /* fireflies first: a mean with infinite variance neither falls as 1/spp nor tests for bias */
    int heavy = heavy_tailed(f, v, out);
    if (!heavy && out->samples_vary[v] && f->n_seeds > 1) { /* one seed: no spread, no claim */
        by_samples(f, v, order);
        for (int i = 1; i < f->n_points; i++) { /* the geometric means the chart and table show */
            double r0 = out->point_rel[v * f->n_points + order[i - 1]],
                   r1 = out->point_rel[v * f->n_points + order[i]];
            double s0 = verdict_mean(f, f->spp, v, order[i - 1]), s1 = verdict_mean(f, f->spp, v, order[i]);
            if (!(r0 > 0 && r1 > 0 && s1 > s0 * VERDICT_SAMPLES_VARY))
                continue;
            double local = log(r1 / r0) / log(s1 / s0);
            if (local > VERDICT_STALL_SLOPE) {
                verdict_say_failure(f, out, VERDICT_STALLS, v, order[i], local, 0);
                break;
            }
        }
    }
    uint64_t dropped = 0;
    for (int p = 0; p < f->n_points; p++)
        for (int k = 0; k < f->n_seeds; k++)
            dropped += f->nonfinite[verdict_at(f, v, p, k)];
    if (dropped)
        verdict_say_failure(f, out, VERDICT_NONFINITE, v, -1, (double)dropped, 0);
    at = -1, most = 0;
    for (int p = 0; p < f->n_points; p++)
        if (verdict_mean(f, f->sampler_share, v, p) > most)
            most = verdict_mean(f, f->sampler_share, v, p), at = p;
    if (most > VERDICT_SAMPLER_SHARE)
        verdict_say_failure(f, out, VERDICT_SHARE, v, at, most, 0);
    if (!heavy)
        bias_of(f, v, out);
}

int verdict_scene_compute(const struct verdict_figures *given, struct verdict_scene *out, struct err *e)
{
    struct verdict_figures g = *given;
    const struct verdict_figures *f = &g;
    double densest = 0;
    for (int i = 0; i < g.n_variants * g.n_points * g.n_seeds; i++)
        densest = fmax(densest, g.spp[i]);
    if (g.ref.relmse > 0 && g.ref.spp > 0 && g.ref.spp < VERDICT_REF_FACTOR * densest)
        g.ref.relmse = NAN, g.ref_noise_refused = 1;
    int nv = f->n_variants;
    size_t per = (size_t)nv * f->n_points;
    *out = (struct verdict_scene){.n_variants = nv,
                                  .n_points = f->n_points,
                                  .n_seeds = f->n_seeds,
                                  .ref_relmse = given->ref.relmse,
                                  .rank_by = f->rank_by};
    snprintf(out->study, sizeof out->study, "%s", f->study);
    snprintf(out->scene, sizeof out->scene, "%s", f->scene);
    out->variants = calloc((size_t)nv, sizeof *out->variants);
    out->by_samples.e = calloc((size_t)nv, sizeof *out->by_samples.e);
    out->by_cpu.e = calloc((size_t)nv, sizeof *out->by_cpu.e);
    out->by_slope.e = calloc((size_t)nv, sizeof *out->by_slope.e);
    out->failures = calloc((size_t)nv * VERDICT_FAILURE_KINDS, sizeof *out->failures);
    out->repeat = calloc(per, sizeof *out->repeat), out->repeat_bias = calloc(per, sizeof *out->repeat_bias);
    out->samples_vary = calloc((size_t)nv, sizeof *out->samples_vary);
    out->warnings = calloc((size_t)VERDICT_SAY_MAX, sizeof *out->warnings);
    out->sentences = calloc((size_t)VERDICT_SAY_MAX, sizeof *out->sentences);
    int *order = calloc((size_t)f->n_points, sizeof *order);
    double *scratch = calloc((size_t)f->n_seeds + 1, sizeof *scratch);
    if (!out->variants || !out->by_samples.e || !out->by_cpu.e || !out->by_slope.e || !out->failures ||
        !out->warnings || !out->sentences || !order || !out->repeat || !out->repeat_bias ||
        !out->samples_vary || !scratch)
        goto fail;
    for (int v = 0; v < nv; v++) {
        snprintf(out->variants[v], sizeof out->variants[v], "%s", f->variants[v]);
        out->samples_vary[v] = samples_vary(f, v);
    }
    repeat_shares(f, out);
    if (verdict_time_points(f, out) < 0 || verdict_time_rank(f, out, &out->by_cpu) < 0)
        goto fail;
    rank_at(f, f->spp, scratch, &out->by_samples);
    rank_slopes(f, &out->by_slope);
    for (int v = 0; v < nv; v++)
        failures_of(f, v, order, out);
    if (verdict_spectrum_compute(f, out) < 0)
        goto fail;
    verdict_say_warnings(f, out);
    verdict_say_sentences(f, out);
    if (verdict_look_compute(f, out) < 0)
        goto fail;
    free(order);
    free(scratch);
    return 0;
fail:
    free(order);
    free(scratch);
    verdict_scene_free(out);
    return err_set(e, NULL, 0, 0, "out of memory");
}
