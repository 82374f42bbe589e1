/* report_stability: a variant's stability line, from the verdict's findings. */
#include "report_stability.h"

#include <math.h>
#include <stdlib.h>

#include "base/sbuf.h"
#include "study/judge/compare_stats.h"

/* The verdict's figure of (v, p): the geometric mean over seeds, the reference's noise taken out. */
static double gm(const struct verdict_scene *vs, int v, int p)
{
    return vs->point_rel ? vs->point_rel[v * vs->n_points + p] : NAN;
}

/* The slope and where error stops falling, or relMSE point by point when the sweep leaves the
   samples alone. a[] is in point order. */
static void convergence(struct sbuf *b, const struct compare *c, const struct verdict_scene *vs, int v,
                        const int *order, const struct compare_agg *a)
{
    int last = c->n_points - 1;
    if (!vs->samples_vary[v]) {
        sbuf_printf(b, "; samples per pixel stay at about %.0f along the sweep, so relMSE point by point: ",
                    a[0].spp);
        for (int i = 0; i < c->n_points; i++)
            sbuf_printf(b, "%s%s: %.3g", i ? ", " : "", c->points[order[i]], gm(vs, v, order[i]));
        return;
    }
    const struct verdict_entry *e = verdict_entry_of(&vs->by_slope, v);
    if (e && isfinite(e->value) && isfinite(e->se))
        sbuf_printf(b, "; relMSE ~ spp^%.2f (per-seed fits, standard error %.2f)", e->value, e->se);
    else if (e && isfinite(e->value)) /* one seed: one fit, no spread */
        sbuf_printf(b, "; relMSE ~ spp^%.2f (one seed's fit)", e->value);
    const struct verdict_failure *x = verdict_failure_of(vs, v, VERDICT_STALLS);
    if (x)
        sbuf_printf(b, "; error stops falling at %s (local slope %.2f)", c->points[x->point], x->value);
    else
        sbuf_printf(b, "; error keeps falling down to %s (%.3g at %.0f spp)", c->points[order[last]],
                    gm(vs, v, order[last]), a[last].spp);
}

/* The share of the error that repeats in every seed at each point, split into bias and pattern. */
static void repeated(struct sbuf *b, const struct compare *c, const struct verdict_scene *vs, int v,
                     const int *order)
{
    int shown = 0;
    for (int i = 0; i < c->n_points; i++) {
        int p = order[i];
        double share = vs->repeat[v * vs->n_points + p], bias = vs->repeat_bias[v * vs->n_points + p];
        if (!isfinite(share))
            continue;
        sbuf_printf(b, "%s%.0f%% at %s",
                    shown++ ? ", " : "; the share of the error that repeats in every seed: ", 100 * share,
                    c->points[p]);
        if (isfinite(bias) && share > 0)
            sbuf_printf(b, " (bias %.0f%%, pattern %.0f%%)", 100 * bias, 100 * (share - bias));
    }
    if (verdict_failure_of(vs, v, VERDICT_STRUCTURED))
        sbuf_printf(b, ": structured error (aliasing, a pattern, or a bias)");
    const struct verdict_failure *x = verdict_failure_of(vs, v, VERDICT_BIASED);
    if (x)
        sbuf_printf(b, "; biased: mean radiance %+.2f%% off the reference at %s", x->value,
                    c->points[x->point]);
    if (isfinite(vs->ref_relmse))
        sbuf_printf(b, " (the reference's own relMSE, %.3g, taken out)", vs->ref_relmse);
}

char *report_stability(const struct compare *c, int s, int v)
{
    int *order = calloc((size_t)c->n_points, sizeof *order);
    struct compare_agg *a = calloc((size_t)c->n_points, sizeof *a);
    const struct verdict_scene *vs = c->has_verdict && s < c->verdict.n_scenes ? &c->verdict.scenes[s] : NULL;
    struct sbuf b = {0};
    if (!order || !a)
        goto done;
    compare_stats_point_order(c, s, v, order);
    for (int i = 0; i < c->n_points; i++)
        compare_stats_aggregate(c, s, v, order[i], &a[i]);
    if (c->scenes[s].ref_kind == COMPARE_REF_NONE || a[0].n == 0) {
        sbuf_printf(&b, "no reference, so no error to judge stability by");
        goto done;
    }
    if (!vs) {
        sbuf_printf(&b, "no verdict, so no figures across seeds");
        goto done;
    }
    /* The 95% interval of the geometric mean, widest over the sweep, as a factor either side. */
    double widest = 1;
    int at = 0;
    for (int i = 0; i < c->n_points && vs->point_rel; i++) {
        int k = v * vs->n_points + order[i];
        if (vs->point_rel[k] > 0 && vs->point_rel_hi[k] / vs->point_rel[k] > widest)
            widest = vs->point_rel_hi[k] / vs->point_rel[k], at = order[i];
    }
    if (c->n_seeds > 1)
        sbuf_printf(&b,
                    "relMSE over %d seeds known within a factor %.2f either way (95%% interval of the "
                    "geometric mean, widest at %s)",
                    c->n_seeds, widest, c->points[at]);
    else
        sbuf_printf(&b, "one seed, so no spread measured");
    if (c->n_points > 1)
        convergence(&b, c, vs, v, order, a);
    repeated(&b, c, vs, v, order);
done:
    free(order);
    free(a);
    return sbuf_take(&b);
}
