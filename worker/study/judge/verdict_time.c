/* verdict_time: per-point figures with 95% intervals, and equal CPU time with the cost's uncertainty. */
#include "verdict_time.h"

#include <math.h>
#include <stdlib.h>

#include "verdict_center.h"
#include "verdict_rank.h"

/* The cost design's blocks, or without one each seed's image as a block of its own. */
static int blocks(const struct verdict_figures *f)
{
    return f->cost_s ? f->n_blocks : f->n_seeds;
}

/* (v, p)'s CPU seconds per image timed in block b. */
static double block_cost(const struct verdict_figures *f, int v, int p, int b)
{
    return f->cost_s ? f->cost_s[verdict_cost_at(f, v, p, b)] : f->cpu_s[verdict_at(f, v, p, b)];
}

/* exp(mean) and exp(mean +- t975 x se) into v, lo, hi (lo = hi = v with one figure). */
static void interval(double mean, double var_of_mean, double df, double *v, double *lo, double *hi)
{
    double half = df > 0 && isfinite(var_of_mean) ? verdict_t_975(df) * sqrt(var_of_mean) : 0;
    *v = exp(mean), *lo = exp(mean - half), *hi = exp(mean + half);
}

int verdict_time_points(const struct verdict_figures *f, struct verdict_scene *out)
{
    size_t per = (size_t)f->n_variants * f->n_points;
    int nb = blocks(f), n = f->n_seeds > nb ? f->n_seeds : nb;
    double *x = calloc((size_t)n + 1, sizeof *x);
    out->point_rel = calloc(per, sizeof(double)), out->point_rel_lo = calloc(per, sizeof(double));
    out->point_rel_hi = calloc(per, sizeof(double)), out->cost = calloc(per, sizeof(double));
    if (!x || !out->point_rel || !out->point_rel_lo || !out->point_rel_hi || !out->cost) {
        free(x);
        return -1;
    }
    out->cost_from_images = f->cost_from_images || !f->cost_s;
    for (int v = 0; v < f->n_variants; v++)
        for (int p = 0; p < f->n_points; p++) {
            size_t i = (size_t)v * f->n_points + p;
            double mean, var;
            for (int k = 0; k < f->n_seeds; k++) {
                double y = verdict_rel(f, verdict_at(f, v, p, k));
                x[k] = y > 0 ? log(y) : NAN;
            }
            int m = verdict_center(x, f->n_seeds, f->rank_by, &mean, &var);
            interval(mean, var, m - 1, &out->point_rel[i], &out->point_rel_lo[i], &out->point_rel_hi[i]);
            for (int b = 0; b < nb; b++) {
                double c = block_cost(f, v, p, b);
                x[b] = c > 0 ? log(c) : NAN;
            }
            verdict_center(x, nb, VERDICT_RANK_MEAN, &mean, &var);
            out->cost[i] = exp(mean);
        }
    free(x);
    return 0;
}

/* How variant v is read at the common log time: per seed y[k] (log relMSE), and the weights g of
   its points' log costs in it (dy/dX, the same for every seed). */
struct reading {
    double *y; /* n_seeds */
    double *g; /* n_points */
    int extrapolated, untold;
};

/* The mean log cost of (v, p) over the blocks: X. */
static double log_cost(const struct verdict_scene *out, int np, int v, int p)
{
    double c = out->cost[v * np + p];
    return c > 0 ? log(c) : NAN;
}

/* Whether (v, p) has a cost and some seed's error. */
static int usable(const struct verdict_figures *f, const struct verdict_scene *out, int v, int p)
{
    int any = 0;
    for (int k = 0; k < f->n_seeds; k++)
        any |= verdict_rel(f, verdict_at(f, v, p, k)) > 0;
    return any && isfinite(log_cost(out, f->n_points, v, p));
}

static void read_at(const struct verdict_figures *f, const struct verdict_scene *out, int v, double at,
                    struct reading *rd)
{
    int np = f->n_points, lo = -1, hi = -1, first = -1, second = -1, last = -1;
    for (int p = 0; p < np; p++)
        rd->g[p] = 0;
    for (int p = 0; p < np; p++) { /* the points around `at`, and the two cheapest and the dearest */
        if (!usable(f, out, v, p))
            continue;
        double x = log_cost(out, np, v, p);
        if (x <= at && (lo < 0 || x > log_cost(out, np, v, lo)))
            lo = p;
        if (x >= at && (hi < 0 || x < log_cost(out, np, v, hi)))
            hi = p;
        if (first < 0 || x < log_cost(out, np, v, first))
            second = first, first = p;
        else if (second < 0 || x < log_cost(out, np, v, second))
            second = p;
        if (last < 0 || x > log_cost(out, np, v, last))
            last = p;
    }
    for (int k = 0; k < f->n_seeds; k++)
        rd->y[k] = NAN;
    if (first < 0 || (lo < 0 && hi < 0)) {
        rd->untold = 1;
        return;
    }
    double span = log_cost(out, np, v, last) - log_cost(out, np, v, first);
    int p1 = lo, p2 = hi;
    if (lo < 0) { /* `at` below its cheapest point: along its first segment, as far as its points span */
        p1 = first, p2 = second;
        rd->extrapolated = 1;
        double beyond = log_cost(out, np, v, first) - at;
        if (second < 0 || !(span > 1e-9)) { /* one point: relMSE x time, within a small step */
            rd->untold = beyond > log(VERDICT_TIME_ONE_POINT);
            p2 = first;
        } else
            rd->untold = beyond > span;
    }
    if (rd->untold)
        return;
    if (p1 == p2 && p1 >= 0 && !rd->extrapolated) { /* at one of its points: the segment below it, or above */
        int below = -1;
        for (int p = 0; p < np; p++)
            if (usable(f, out, v, p) && log_cost(out, np, v, p) < log_cost(out, np, v, p1) &&
                (below < 0 || log_cost(out, np, v, p) > log_cost(out, np, v, below)))
                below = p;
        if (below >= 0)
            p1 = below;
        else if (second >= 0)
            p2 = second;
    }
    double x1 = log_cost(out, np, v, p1), x2 = log_cost(out, np, v, p2);
    if (p1 == p2 || !(x2 - x1 > 1e-12)) { /* at its point, or one point read with slope -1 */
        for (int k = 0; k < f->n_seeds; k++) {
            double y = verdict_rel(f, verdict_at(f, v, p1, k));
            rd->y[k] = y > 0 ? log(y) + (x1 - at) : NAN;
        }
        rd->g[p1] = 1;
        return;
    }
    double w = (at - x1) / (x2 - x1), s1 = 0, s2 = 0;
    int m = 0;
    for (int k = 0; k < f->n_seeds; k++) {
        double a = verdict_rel(f, verdict_at(f, v, p1, k)), b = verdict_rel(f, verdict_at(f, v, p2, k));
        if (!(a > 0 && b > 0))
            continue;
        rd->y[k] = (1 - w) * log(a) + w * log(b);
        s1 += log(a), s2 += log(b), m++;
    }
    double slope = m ? (s2 - s1) / m / (x2 - x1) : 0; /* the seeds' mean line: d y / d X */
    rd->g[p1] = -slope * (1 - w), rd->g[p2] = -slope * w;
}

/* The variance of the cost part of sum_p ga[p] X_ap - gb[p] X_bp, from its per-block values (paired
   by block); b < 0: variant a alone. Its degrees of freedom into *df. */
static double cost_var(const struct verdict_figures *f, int a, const double *ga, int b, const double *gb,
                       double *lb, double *df)
{
    for (int k = 0; k < blocks(f); k++) {
        double l = 0;
        for (int p = 0; p < f->n_points; p++) {
            if (ga[p] != 0)
                l += ga[p] * log(block_cost(f, a, p, k));
            if (b >= 0 && gb[p] != 0)
                l -= gb[p] * log(block_cost(f, b, p, k));
        }
        lb[k] = l;
    }
    double mean, var;
    int m = verdict_center(lb, blocks(f), VERDICT_RANK_MEAN, &mean, &var);
    *df = m - 1;
    return m > 1 ? var : 0;
}

/* Two-sided p of D = y_a - y_b with both variances: the seeds' paired differences, the blocks'. */
static double pair_p(const struct verdict_figures *f, int a, const struct reading *ra, int b,
                     const struct reading *rb, double *tmp)
{
    if (ra->untold || rb->untold)
        return 1;
    for (int k = 0; k < f->n_seeds; k++)
        tmp[k] = ra->y[k] - rb->y[k];
    double d, ve, df_c, vc;
    int m = verdict_center(tmp, f->n_seeds, f->rank_by, &d, &ve);
    if (m < 2)
        return 1;
    vc = blocks(f) > 1 ? cost_var(f, a, ra->g, b, rb->g, tmp, &df_c) : (df_c = 0);
    double v = ve + vc;
    if (!(v > 0))
        return d == 0 ? 1 : 0;
    double den = ve * ve / (m - 1) + (df_c > 0 ? vc * vc / df_c : 0);
    return verdict_t_p(d / sqrt(v), den > 0 ? v * v / den : m - 1);
}

int verdict_time_rank(const struct verdict_figures *f, const struct verdict_scene *out,
                      struct verdict_ranking *r)
{
    int nv = f->n_variants, ns = f->n_seeds, np = f->n_points, rc = -1;
    int tmp_n = ns > blocks(f) ? ns : blocks(f);
    struct reading *rd = calloc((size_t)nv, sizeof *rd);
    double *mem = calloc((size_t)nv * (ns + np) + tmp_n + 1, sizeof *mem);
    r->pair_p = calloc((size_t)nv * nv, sizeof *r->pair_p);
    if (!rd || !mem || !r->pair_p)
        goto done;
    double at = INFINITY, *tmp = mem + (size_t)nv * (ns + np);
    for (int v = 0; v < nv; v++) { /* the most every variant reached */
        double most = -INFINITY;
        for (int p = 0; p < np; p++)
            if (usable(f, out, v, p))
                most = fmax(most, log_cost(out, np, v, p));
        if (isfinite(most))
            at = fmin(at, most);
    }
    r->at = exp(at), r->n = nv, r->pair_n = nv;
    for (int v = 0; v < nv; v++) {
        rd[v] = (struct reading){.y = mem + (size_t)v * (ns + np), .g = mem + (size_t)v * (ns + np) + ns};
        if (isfinite(at))
            read_at(f, out, v, at, &rd[v]);
        else
            rd[v].untold = 1;
        struct verdict_entry *e = &r->e[v];
        verdict_entry_start(e, v);
        e->extrapolated = rd[v].extrapolated, e->untold = rd[v].untold;
        double mean, ve, df_c = 0, vc = 0;
        int m = verdict_center(rd[v].y, ns, f->rank_by, &mean, &ve);
        if (!rd[v].untold && m > 0 && blocks(f) > 1)
            vc = cost_var(f, v, rd[v].g, -1, NULL, tmp, &df_c);
        e->n = m, e->mean = m ? mean : NAN;
        double var = (m > 1 ? ve : 0) + vc,
               den = (m > 1 ? ve * ve / (m - 1) : 0) + (df_c > 0 ? vc * vc / df_c : 0);
        e->se = m > 1 ? sqrt(var) : NAN;
        if (m > 0)
            interval(mean, m > 1 ? var : NAN, den > 0 ? var * var / den : 0, &e->value, &e->lo, &e->hi);
        else
            e->value = e->lo = e->hi = NAN;
    }
    for (int a = 0; a < nv; a++) /* one figure per pair, both ways: Holm's cut compares it bit for bit */
        for (int b = a; b < nv; b++)
            r->pair_p[a * nv + b] = r->pair_p[b * nv + a] = a == b ? 1 : pair_p(f, a, &rd[a], b, &rd[b], tmp);
    verdict_rank(r);
    rc = 0;
done:
    free(rd);
    free(mem);
    return rc;
}
