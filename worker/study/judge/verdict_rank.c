/* verdict_rank: rank variants best first, apart only where Welch's t test, Holm-corrected across
   the ranking's pairs, says their seeds' means differ. */
#include "verdict_rank.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

void verdict_entry_start(struct verdict_entry *e, int v)
{
    *e = (struct verdict_entry){.variant = v, .lo = INFINITY, .hi = -INFINITY};
}

void verdict_entry_add(struct verdict_entry *e, double y, int log_scale)
{
    if (!isfinite(y) || (log_scale && !(y > 0)))
        return;
    e->lo = fmin(e->lo, y), e->hi = fmax(e->hi, y);
    double x = log_scale ? log(y) : y, d = x - e->mean; /* Welford's running mean and sum of squares */
    e->n++;
    e->mean += d / e->n;
    e->m2 += d * (x - e->mean);
}

void verdict_entry_end(struct verdict_entry *e, int log_scale)
{
    if (e->n == 0) {
        e->value = e->lo = e->hi = e->mean = e->se = NAN;
        return;
    }
    e->value = log_scale ? exp(e->mean) : e->mean;
    e->se = e->n > 1 ? sqrt(e->m2 / (e->n - 1) / e->n) : NAN;
    double half = e->n > 1 ? verdict_t_975(e->n - 1) * e->se : 0; /* the 95% interval */
    e->lo = log_scale ? exp(e->mean - half) : e->mean - half;
    e->hi = log_scale ? exp(e->mean + half) : e->mean + half;
}

/* The continued fraction of the incomplete beta function (Abramowitz and Stegun 26.5.8),
   evaluated by Lentz's method; converges fast for x < (a + 1) / (a + b + 2). */
static double beta_fraction(double x, double a, double b)
{
    const double tiny = 1e-300;
    double c = 1, d = 1 - (a + b) * x / (a + 1);
    d = 1 / (fabs(d) < tiny ? tiny : d);
    double h = d;
    for (int m = 1; m <= 300; m++) {
        for (int odd = 0; odd < 2; odd++) {
            double k = odd ? -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))
                           : m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m));
            d = 1 + k * d;
            d = 1 / (fabs(d) < tiny ? tiny : d);
            c = 1 + k / c;
            c = fabs(c) < tiny ? tiny : c;
            h *= d * c;
            if (odd && fabs(d * c - 1) < 1e-14)
                return h;
        }
    }
    return h;
}

/* The regularised incomplete beta function I_x(a, b). */
static double beta_inc(double x, double a, double b)
{
    if (x <= 0)
        return 0;
    if (x >= 1)
        return 1;
    double front = exp(lgamma(a + b) - lgamma(a) - lgamma(b) + a * log(x) + b * log1p(-x));
    if (x < (a + 1) / (a + b + 2))
        return front * beta_fraction(x, a, b) / a;
    return 1 - front * beta_fraction(1 - x, b, a) / b;
}

double verdict_welch_p(const struct verdict_entry *a, const struct verdict_entry *b)
{
    if (a->n < 2 || b->n < 2 || !isfinite(a->mean) || !isfinite(b->mean))
        return 1;
    double va = a->se * a->se, vb = b->se * b->se, v = va + vb;
    if (!(v > 0))
        return a->mean == b->mean ? 1 : 0;
    double t = (a->mean - b->mean) / sqrt(v);
    /* Welch-Satterthwaite degrees of freedom */
    double df = v * v / (va * va / (a->n - 1) + vb * vb / (b->n - 1));
    return verdict_t_p(t, df);
}

double verdict_t_p(double t, double df)
{
    if (!(df > 0) || isnan(t))
        return 1;
    return beta_inc(df / (df + t * t), df / 2, 0.5); /* Student's t tail as an incomplete beta function */
}

double verdict_t_975(double df)
{
    if (!(df > 0))
        return NAN;
    double lo = 0, hi = 1e3;
    for (int i = 0; i < 100; i++) { /* bisection: the two-sided p falls as t grows */
        double mid = (lo + hi) / 2;
        if (verdict_t_p(mid, df) > 0.05)
            lo = mid;
        else
            hi = mid;
    }
    return (lo + hi) / 2;
}

/* The p-value r separates a and b by: r->pair_p's when set, else Welch's on the entries. */
static double pair_p(const struct verdict_ranking *r, const struct verdict_entry *a,
                     const struct verdict_entry *b)
{
    if (r->pair_p && a->variant < r->pair_n && b->variant < r->pair_n)
        return r->pair_p[a->variant * r->pair_n + b->variant];
    return verdict_welch_p(a, b);
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* Holm's step-down procedure over the pairs of r that are compared (both reached or both not):
   the largest p-value it rejects, so a pair is separated when its p <= the cut; -1 when none is. */
static double holm_cut(const struct verdict_ranking *r)
{
    int m = 0;
    double *p = malloc(sizeof *p * (size_t)(r->n * (r->n - 1) / 2 + 1)), cut = -1;
    if (!p)
        return -1; /* out of memory: nothing separated, the cautious answer */
    for (int i = 0; i < r->n; i++)
        for (int j = i + 1; j < r->n; j++)
            if (r->e[i].unreached == r->e[j].unreached)
                p[m++] = pair_p(r, &r->e[i], &r->e[j]);
    qsort(p, (size_t)m, sizeof *p, cmp_double);
    for (int k = 0; k < m && p[k] <= VERDICT_ALPHA / (m - k); k++)
        cut = p[k];
    free(p);
    return cut;
}

int verdict_beats(const struct verdict_ranking *r, const struct verdict_entry *a,
                  const struct verdict_entry *b)
{
    if (a->unreached != b->unreached)
        return b->unreached;
    return r->p_cut >= 0 && a->mean < b->mean && pair_p(r, a, b) <= r->p_cut;
}

/* Whether x goes before y: fewer beaten-by, then the lower mean (not measured last). */
static int before(const struct verdict_entry *x, const struct verdict_entry *y)
{
    if (x->rank != y->rank)
        return x->rank < y->rank;
    if (x->unreached != y->unreached)
        return y->unreached;
    return x->mean < y->mean || (isfinite(x->mean) && !isfinite(y->mean));
}

void verdict_rank(struct verdict_ranking *r)
{
    r->p_cut = holm_cut(r);
    int first = 0, spread = 0;
    for (int i = 0; i < r->n; i++)
        spread |= r->e[i].n > 1;
    for (int i = 0; i < r->n; i++) { /* one seed each: no spread, nothing told apart */
        r->e[i].rank = 1;
        for (int j = 0; j < r->n; j++)
            r->e[i].rank += spread && verdict_beats(r, &r->e[j], &r->e[i]);
        first += r->e[i].rank == 1;
    }
    /* Separation is not transitive: a wide spread at a worse mean may be beaten by none though a
       narrower one before it is. Best first is by rank, then mean (an insertion sort: a handful). */
    for (int i = 1; i < r->n; i++)
        for (int j = i; j > 0 && before(&r->e[j], &r->e[j - 1]); j--) {
            struct verdict_entry t = r->e[j];
            r->e[j] = r->e[j - 1];
            r->e[j - 1] = t;
        }
    r->status = first == r->n ? VERDICT_INCONCLUSIVE : first == 1 ? VERDICT_CLEAR : VERDICT_TIE;
}

/* The two add (their noise is independent), so the difference is the variant's own. Floored at 1%
   of the measured value, so a point drowned in the reference's noise (warned) still has a logarithm. */
double verdict_rel(const struct verdict_figures *f, int i)
{
    double y = f->relmse[i];
    return f->ref.relmse > 0 && isfinite(y) ? fmax(y - f->ref.relmse, 0.01 * y) : y;
}

void verdict_ranking_winner(const struct verdict_scene *v, const struct verdict_ranking *r, int tie_note,
                            char *buf, size_t n)
{
    size_t len = 0;
    buf[0] = 0;
    if (r->n == 0 || r->status == VERDICT_INCONCLUSIVE) {
        snprintf(buf, n, "inconclusive");
        return;
    }
    for (int i = 0; i < r->n && r->e[i].rank == 1 && len < n; i++)
        len += (size_t)snprintf(buf + len, n - len, "%s%s", i ? " = " : "", v->variants[r->e[i].variant]);
    if (tie_note && r->status == VERDICT_TIE && len < n)
        snprintf(buf + len, n - len, " (tie)");
}
