/* compare_stats: means and spread of a compare job's figures, and its seed images taken together. */
#include "compare_stats.h"
#include "verdict.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image/errspec.h"
#include "image/imgio.h"

/* Whether value i (pixel i / 3) of img counts under mask (every one without). */
static int on(const struct rgbf *img, const struct img_mask *mask, size_t i)
{
    return mask_on(mask, (int)(i / 3 % (size_t)img->w), (int)(i / 3 / (size_t)img->w));
}

void compare_stats_aggregate(const struct compare *c, int s, int v, int p, struct compare_agg *a)
{
    *a = (struct compare_agg){0};
    for (int k = 0; k < c->n_seeds; k++) {
        const struct study_result *r = &c->results.rows[compare_index(c, s, v, p, k)];
        if (!r->done)
            continue;
        a->n++;
        a->spp += r->spp_mean;
        a->cpu_s += r->cpu_s;
        if (r->has_error)
            a->rel += r->error.relmse;
    }
    if (a->n) {
        a->spp /= a->n;
        a->cpu_s /= a->n;
        a->rel /= a->n;
    }
}

/* Whether v's sweep points in scene s change its samples per pixel (verdict_samples_vary). */
static int samples_vary(const struct compare *c, int s, int v)
{
    double lo = INFINITY, hi = 0;
    struct compare_agg a;
    for (int p = 0; p < c->n_points; p++) {
        compare_stats_aggregate(c, s, v, p, &a);
        if (a.n > 0)
            lo = fmin(lo, a.spp), hi = fmax(hi, a.spp);
    }
    return verdict_samples_vary(lo, hi);
}

void compare_stats_point_order(const struct compare *c, int s, int v, int *order)
{
    struct compare_agg a, b;
    for (int p = 0; p < c->n_points; p++)
        order[p] = p;
    if (!samples_vary(c, s, v)) /* the sweep's own order: sorting by noise would scramble it */
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

double compare_stats_mean_radiance(const struct rgbf *img, const struct img_mask *mask)
{
    size_t n = (size_t)img->w * img->h * 3, counted = 0;
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        if (on(img, mask, i))
            sum += img->px[i], counted++;
    return counted ? sum / (double)counted : NAN;
}

/* The path of seed image it's pixels in dir: its float copy when the reference is linear. */
static void image_path(const struct compare *c, int s, const struct compare_item *it, const char *dir,
                       char *path, size_t n)
{
    const char *dot = strrchr(it->job.output, '.');
    int stem = dot ? (int)(dot - it->job.output) : (int)strlen(it->job.output);
    if (c->scenes[s].ref_domain == IMG_LINEAR)
        snprintf(path, n, "%s/%.*s.exr", dir, stem, it->job.output);
    else
        snprintf(path, n, "%s/%s", dir, it->job.output);
}

int compare_stats_seed_images(const struct compare *c, int s, int v, int p, const char *dir,
                              const struct rgbf *ref, struct compare_seed_stats *out, struct err *e)
{
    size_t n = (size_t)ref->w * ref->h * 3;
    const struct img_mask *mask = c->scenes[s].mask;
    const size_t side2 = (size_t)ERRSPEC_MAX_SIDE * ERRSPEC_MAX_SIDE;
    double *sum = calloc(n, sizeof *sum), *pooled = calloc(side2, sizeof *pooled),
           *one = calloc(side2, sizeof *one);
    int rc = -1, sw = 0, sh = 0, spec_ok = out->spec_ring != NULL;
    out->peak_p = out->anisotropy = NAN;
    if (!sum || !pooled || !one) {
        free(sum), free(pooled), free(one);
        return err_set(e, NULL, 0, 0, "out of memory");
    }
    for (int k = 0; k < c->n_seeds; k++) {
        char path[4096];
        struct rgbf img = {0};
        image_path(c, s, &c->items[compare_index(c, s, v, p, k)], dir, path, sizeof path);
        if (imgio_read_f(path, &img, NULL, e) < 0)
            goto done;
        if (img.w != ref->w || img.h != ref->h) {
            image_f_free(&img);
            err_set(e, path, 0, 0, "image is %dx%d, the reference %dx%d", img.w, img.h, ref->w, ref->h);
            goto done;
        }
        for (size_t i = 0; i < n; i++)
            sum[i] += img.px[i];
        out->radiance[k] = compare_stats_mean_radiance(&img, mask);
        if (spec_ok) { /* the seed's own spectrum (for the band) and the pool (for the judgment) */
            struct errspec_look l;
            for (size_t i = 0; i < side2; i++)
                one[i] = 0;
            spec_ok = errspec_power_add(ref, &img, one, &sw, &sh, e) == 0;
            errspec_look_of(one, sw, sh, 1, &l);
            for (int r = 0; r < VERDICT_SPEC_RINGS; r++)
                out->spec_ring[(size_t)k * VERDICT_SPEC_RINGS + r] = l.ring[r] > 0 ? log10(l.ring[r]) : NAN;
            for (size_t i = 0; i < side2; i++)
                pooled[i] += one[i];
        }
        image_f_free(&img);
    }
    double rel = 0, mean = 0, ref_mean = compare_stats_mean_radiance(ref, mask), bias = 0;
    size_t counted = 0;
    for (size_t i = 0; i < n; i++)
        counted += on(ref, mask, i);
    for (size_t i = 0; i < n; i++) {
        if (!on(ref, mask, i))
            continue;
        double a = ref->px[i], d = sum[i] / c->n_seeds - a;
        rel += d * d / (a * a + METRICS_REL_EPS);
        mean += sum[i] / c->n_seeds / (double)counted;
    }
    /* the offset alone: the reference scaled to the mean image's mean radiance */
    double scale = ref_mean > 0 ? mean / ref_mean - 1 : 0;
    for (size_t i = 0; i < n; i++) {
        double a = ref->px[i], d = scale * a;
        bias += on(ref, mask, i) ? d * d / (a * a + METRICS_REL_EPS) : 0;
    }
    out->rel_of_mean = rel / (double)counted;
    out->bias_rel = bias / (double)counted;
    if (spec_ok) {
        struct errspec_look l;
        errspec_look_of(pooled, sw, sh, c->n_seeds, &l);
        out->peak_p = l.peak_p, out->anisotropy = l.anisotropy;
    }
    rc = 0;
done:
    free(sum), free(pooled), free(one);
    return rc;
}
