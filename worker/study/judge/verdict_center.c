/* verdict_center: the mean or the median of the seeds' figures, and its variance. */
#include "verdict_center.h"

#include <math.h>

#include "verdict_rank.h"

/* The k-th smallest (0-based) of x's finite values, by counting (no copy: seeds are few). */
static double kth(const double *x, int n, int k)
{
    for (int i = 0; i < n; i++) {
        if (!isfinite(x[i]))
            continue;
        int less = 0, leq = 0;
        for (int j = 0; j < n; j++)
            if (isfinite(x[j]))
                less += x[j] < x[i], leq += x[j] <= x[i];
        if (less <= k && k < leq)
            return x[i];
    }
    return NAN;
}

int verdict_center(const double *x, int n, enum verdict_rank_by by, double *center, double *var_of_center)
{
    double s = 0, ss = 0;
    int m = 0;
    for (int i = 0; i < n; i++)
        if (isfinite(x[i]))
            s += x[i], m++;
    *var_of_center = NAN;
    if (by != VERDICT_RANK_MEDIAN) {
        *center = m ? s / m : NAN;
        for (int i = 0; i < n; i++)
            if (isfinite(x[i]))
                ss += (x[i] - *center) * (x[i] - *center);
        if (m > 1)
            *var_of_center = ss / (m - 1) / m;
        return m;
    }
    *center = m == 0 ? NAN : m % 2 ? kth(x, n, m / 2) : 0.5 * (kth(x, n, m / 2 - 1) + kth(x, n, m / 2));
    if (m > 1) {
        const double z = 1.959964;
        int c = (int)lround((m + 1) / 2.0 - z * sqrt(m / 4.0));
        c = c < 1 ? 1 : c > m / 2 ? m / 2 : c;
        double se = (kth(x, n, m - c) - kth(x, n, c - 1)) / (2 * z);
        *var_of_center = se * se;
    }
    return m;
}

void verdict_entry_logs(struct verdict_entry *e, const double *logs, int n, enum verdict_rank_by by)
{
    double mean, var;
    int m = verdict_center(logs, n, by, &mean, &var);
    e->n = m;
    if (m == 0) {
        e->value = e->lo = e->hi = e->mean = e->se = NAN;
        return;
    }
    e->mean = mean, e->se = m > 1 ? sqrt(var) : NAN;
    double half = m > 1 ? verdict_t_975(m - 1) * e->se : 0;
    e->value = exp(mean), e->lo = exp(mean - half), e->hi = exp(mean + half);
}
