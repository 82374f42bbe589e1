/* compare_stats: means, spread, convergence and structure of a compare job's error. */
#include "compare_stats.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chart.h"
#include "base/fileio.h"
#include "image/imgio.h"
#include "base/sbuf.h"

void compare_stats_aggregate(const struct compare *c, int s, int v, int p, struct compare_agg *a)
{
    *a = (struct compare_agg){0};
    a->rel_lo = INFINITY;
    for (int k = 0; k < c->n_seeds; k++) {
        const struct compare_item *it = &c->items[compare_index(c, s, v, p, k)];
        if (!it->done)
            continue;
        a->n++;
        a->spp += it->spp_mean;
        a->wall_s += it->wall_s;
        a->cpu_s += it->cpu_s;
        if (it->has_error) {
            a->rel += it->error.relmse;
            a->rel_lo = fmin(a->rel_lo, it->error.relmse);
            a->rel_hi = fmax(a->rel_hi, it->error.relmse);
        }
    }
    if (a->n) {
        a->spp /= a->n;
        a->wall_s /= a->n;
        a->cpu_s /= a->n;
        a->rel /= a->n;
    }
    if (!isfinite(a->rel_lo))
        a->rel_lo = 0;
}

/* A sweep "changes the samples" when its points' mean samples per pixel span more than 5%: a
   light_threshold, max_depth or poisson_pool sweep does not, though a poisson pixel sampler's
   counts move by a hair from point to point. */
#define SAMPLES_VARY 1.05

int compare_stats_samples_vary(const struct compare *c, int s, int v)
{
    double lo = INFINITY, hi = 0;
    struct compare_agg a;
    for (int p = 0; p < c->n_points; p++) {
        compare_stats_aggregate(c, s, v, p, &a);
        if (a.n > 0)
            lo = fmin(lo, a.spp), hi = fmax(hi, a.spp);
    }
    return hi > lo * SAMPLES_VARY;
}

void compare_stats_point_order(const struct compare *c, int s, int v, int *order)
{
    struct compare_agg a, b;
    for (int p = 0; p < c->n_points; p++)
        order[p] = p;
    if (!compare_stats_samples_vary(c, s, v)) /* the sweep's own order: sorting by noise would scramble it */
        return;
    for (int i = 1; i < c->n_points; i++) /* insertion sort: a handful of points */
        for (int j = i; j > 0; j--) {
            compare_stats_aggregate(c, s, v, order[j], &a);
            compare_stats_aggregate(c, s, v, order[j - 1], &b);
            if (!(a.spp < b.spp))
                break;
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
}

int compare_stats_seed_average(const struct compare *c, int s, int v, int p, const char *dir,
                               const struct rgbf *ref, double *rel_of_mean, double *mean_rel, struct err *e)
{
    size_t n = (size_t)ref->w * ref->h * 3;
    double *sum = calloc(n, sizeof *sum);
    int rc = -1, k;
    *mean_rel = 0;
    if (!sum)
        return err_set(e, NULL, 0, 0, "out of memory");
    for (k = 0; k < c->n_seeds; k++) {
        const struct compare_item *it = &c->items[compare_index(c, s, v, p, k)];
        char path[4096];
        struct rgbf img = {0};
        const char *dot = strrchr(it->job.output, '.');
        int stem = dot ? (int)(dot - it->job.output) : (int)strlen(it->job.output);
        if (c->scenes[s].ref_domain == IMG_LINEAR)
            snprintf(path, sizeof path, "%s/%.*s.exr", dir, stem, it->job.output);
        else
            snprintf(path, sizeof path, "%s/%s", dir, it->job.output);
        if (imgio_read_f(path, &img, NULL, e) < 0)
            goto done;
        if (img.w != ref->w || img.h != ref->h) {
            image_f_free(&img);
            err_set(e, path, 0, 0, "image is %dx%d, the reference %dx%d", img.w, img.h, ref->w, ref->h);
            goto done;
        }
        for (size_t i = 0; i < n; i++)
            sum[i] += img.px[i];
        image_f_free(&img);
        *mean_rel += it->error.relmse / c->n_seeds;
    }
    double rel = 0;
    for (size_t i = 0; i < n; i++) {
        double a = ref->px[i], d = sum[i] / c->n_seeds - a;
        rel += d * d / (a * a + METRICS_REL_EPS);
    }
    *rel_of_mean = rel / n;
    rc = 0;
done:
    free(sum);
    return rc;
}

double compare_stats_repeat_share(const struct compare *c, int s, int v, int p, const char *dir,
                                  const struct rgbf *ref, double *gain)
{
    double rom, mr;
    struct err e;
    if (c->n_seeds < 2 || compare_stats_seed_average(c, s, v, p, dir, ref, &rom, &mr, &e) < 0 || !(mr > 0))
        return NAN;
    if (gain)
        *gain = rom > 0 ? mr / rom : INFINITY;
    return fmin(1, fmax(0, (c->n_seeds * rom / mr - 1) / (c->n_seeds - 1)));
}

/* Least-squares slope of log relMSE against log samples per pixel over the given points. */
static double slope(const struct compare_agg *a, int n)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int m = 0;
    for (int i = 0; i < n; i++) {
        if (!(a[i].spp > 0 && a[i].rel > 0))
            continue;
        double x = log(a[i].spp), y = log(a[i].rel);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
        m++;
    }
    double den = m * sxx - sx * sx;
    return m >= 2 && den > 0 ? (m * sxy - sx * sy) / den : NAN;
}

char *compare_stats_stability(const struct compare *c, int s, int v, const char *dir, const struct rgbf *ref)
{
    int *order = calloc((size_t)c->n_points, sizeof *order);
    struct compare_agg *a = calloc((size_t)c->n_points, sizeof *a);
    struct sbuf b = {0};
    if (!order || !a)
        goto done;
    compare_stats_point_order(c, s, v, order);
    for (int i = 0; i < c->n_points; i++)
        compare_stats_aggregate(c, s, v, order[i], &a[i]);
    if (!ref || a[0].n == 0) {
        sbuf_printf(&b, "no reference, so no error to judge stability by");
        goto done;
    }
    /* Spread across seeds: (max - min) / mean, largest over the sweep. */
    double spread = 0;
    int at = 0;
    for (int i = 0; i < c->n_points; i++)
        if (a[i].rel > 0 && (a[i].rel_hi - a[i].rel_lo) / a[i].rel > spread)
            spread = (a[i].rel_hi - a[i].rel_lo) / a[i].rel, at = order[i];
    if (c->n_seeds > 1)
        sbuf_printf(&b, "spread across %d seeds at most %.0f%% of the mean relMSE (%s)", c->n_seeds,
                    100 * spread, c->points[at]);
    else
        sbuf_printf(&b, "one seed, so no spread measured");
    if (c->n_points > 1 && !compare_stats_samples_vary(c, s, v)) {
        /* No slope or "stops falling" against samples that do not change: the figures instead. */
        sbuf_printf(&b, "; samples per pixel stay at about %.0f along the sweep, so relMSE point by point: ",
                    a[0].spp);
        for (int i = 0; i < c->n_points; i++)
            sbuf_printf(&b, "%s%s: %.3g", i ? ", " : "", c->points[order[i]], a[i].rel);
    } else if (c->n_points > 1) {
        sbuf_printf(&b, "; relMSE ~ spp^%.2f", slope(a, c->n_points));
        /* Error "stops falling" at the first step whose local slope is above -0.3: more samples
           buy almost nothing there (noise alone falls as spp^-1). */
        int stop = -1;
        double local = 0;
        for (int i = 1; i < c->n_points && stop < 0; i++)
            if (a[i].spp > a[i - 1].spp && a[i].rel > 0 && a[i - 1].rel > 0) {
                local = log(a[i].rel / a[i - 1].rel) / log(a[i].spp / a[i - 1].spp);
                if (local > -0.3)
                    stop = i;
            }
        if (stop > 0)
            sbuf_printf(
                &b, "; error stops falling at %s: %.3g at %.0f spp, then %.3g at %.0f spp (local slope %.2f)",
                c->points[order[stop]], a[stop - 1].rel, a[stop - 1].spp, a[stop].rel, a[stop].spp, local);
        else
            sbuf_printf(&b, "; error keeps falling down to %s (%.3g at %.0f spp)",
                        c->points[order[c->n_points - 1]], a[c->n_points - 1].rel, a[c->n_points - 1].spp);
    }
    /* The share of the error that repeats in every seed, at every point: noise falls by the seed
       count when the seeds' images are averaged, structure (aliasing, a pattern, a bias) does not.
       Uniform's fixed grid repeats at every sample count; at the densest point alone the
       reference's own noise, a floor of a few percent, could hide that. */
    if (c->n_seeds > 1) {
        double gain = 0, share = 0;
        int shown = 0, last = 0;
        for (int i = 0; i < c->n_points; i++) {
            double here = compare_stats_repeat_share(c, s, v, order[i], dir, ref, &gain);
            if (!isfinite(here))
                continue;
            share = here;
            last = order[i];
            sbuf_printf(&b, "%s%.0f%% at %s",
                        shown++ ? ", " : "; the share of the error that repeats in every seed: ", 100 * share,
                        c->points[order[i]]);
        }
        if (shown)
            sbuf_printf(&b, " (averaging the %d seeds divides relMSE by %.2f at %s, pure noise by %d)%s",
                        c->n_seeds, gain, c->points[last], c->n_seeds,
                        share > VERDICT_STRUCTURED_SHARE
                            ? ": structured error (aliasing, a pattern, or a bias)"
                            : "");
    }
done:
    free(order);
    free(a);
    return sbuf_take(&b);
}

char *compare_stats_chart_svg(const struct compare *c)
{
    int ns = c->n_variants, np = c->n_points, nsc = c->n_scenes;
    size_t per = (size_t)nsc * ns * np;
    double *mem = calloc(per * 5, sizeof *mem);
    int *order = calloc((size_t)np, sizeof *order);
    struct chart_series *ser = calloc((size_t)nsc * ns * 2, sizeof *ser);
    struct chart_panel *pan = calloc((size_t)nsc * 2, sizeof *pan);
    char(*titles)[160] = calloc((size_t)nsc * 2, sizeof *titles);
    static const double slopes[] = {-1, -1.5};
    char *svg = NULL, title[256];
    if (!mem || !order || !ser || !pan || !titles)
        goto done;
    double *cpu = mem, *spp = mem + per, *rel = mem + 2 * per, *lo = mem + 3 * per, *hi = mem + 4 * per;
    for (int s = 0; s < nsc; s++) {
        struct chart_series *by_time = ser + (size_t)2 * s * ns, *by_spp = by_time + ns;
        for (int v = 0; v < ns; v++) {
            size_t k0 = ((size_t)s * ns + v) * np;
            compare_stats_point_order(c, s, v, order);
            for (int i = 0; i < np; i++) {
                struct compare_agg a;
                compare_stats_aggregate(c, s, v, order[i], &a);
                size_t k = k0 + i;
                cpu[k] = a.cpu_s, spp[k] = a.spp, rel[k] = a.rel, lo[k] = a.rel_lo, hi[k] = a.rel_hi;
            }
            /* One seed has no spread: a whisker would be a dot claiming one. */
            const double *l = c->n_seeds > 1 ? lo + k0 : NULL, *h = c->n_seeds > 1 ? hi + k0 : NULL;
            by_time[v] = (struct chart_series){c->variants[v], np, cpu + k0, rel + k0, l, h};
            by_spp[v] = (struct chart_series){c->variants[v], np, spp + k0, rel + k0, l, h};
        }
        snprintf(titles[2 * s], sizeof titles[0], "%s: error against CPU time", c->scenes[s].name);
        snprintf(titles[2 * s + 1], sizeof titles[0], "%s: error against samples", c->scenes[s].name);
        const char *note =
            c->scenes[s].ref_kind == COMPARE_REF_NONE ? "no reference given: no error to chart" : NULL;
        pan[2 * s] = (struct chart_panel){titles[2 * s],
                                          "CPU time per image (s, log)",
                                          "relMSE (eps 0.01, log)",
                                          note,
                                          by_time,
                                          ns,
                                          slopes,
                                          2};
        pan[2 * s + 1] = (struct chart_panel){titles[2 * s + 1],
                                              "samples per pixel (mean, log)",
                                              "relMSE (eps 0.01, log)",
                                              note,
                                              by_spp,
                                              ns,
                                              slopes,
                                              2};
    }
    if (c->n_seeds > 1)
        snprintf(title, sizeof title,
                 "%s: relMSE against CPU time and samples per pixel (mean of %d seeds; whiskers: "
                 "min to max)",
                 c->name, c->n_seeds);
    else
        snprintf(title, sizeof title,
                 "%s: relMSE against CPU time and samples per pixel (one seed: no spread across "
                 "seeds measured)",
                 c->name);
    svg = chart_svg(title, pan, 2 * nsc, 2);
done:
    free(mem);
    free(order);
    free(ser);
    free(pan);
    free(titles);
    return svg;
}
