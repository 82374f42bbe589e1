/* compare_spp: samples per pixel to a sampler's threshold, through sampler_capacity. */
#include "compare_spp.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scenefile/yget.h"

/* The threshold whose grid side is n (100 / n to 6 digits, as image names print it, when that
   keeps n; else 100 / n). */
static double side_threshold(int n)
{
    char text[32];
    snprintf(text, sizeof text, "%g", 100.0 / n);
    double t = strtod(text, NULL);
    return sampler_grid_side(t) == n ? t : 100.0 / n;
}

int compare_spp_threshold(enum sampler_kind kind, long spp, double *t, long *below, long *above)
{
    *below = *above = 0;
    if (sampler_traits(kind)->count == SAMPLER_COUNT_BRIDSON) {
        char text[32];
        snprintf(text, sizeof text, "%.4g", sqrt(SAMPLER_POISSON_T2 / (double)spp));
        *t = fmin(strtod(text, NULL), 100.0);
        return 0;
    }
    long root = lround(sqrt((double)spp));
    int found = 0;
    for (int n = 1; n <= 100000; n++) { /* the sets grow with n: stop past spp */
        double tn = side_threshold(n);
        size_t count = sampler_capacity(kind, tn);
        if (count == (size_t)spp && (!found || n == root)) {
            *t = tn;
            found = n;
        } else if (count < (size_t)spp)
            *below = (long)count;
        else if (count > (size_t)spp) {
            *above = count > (size_t)SAMPLER_MAX_POINTS ? 0 : (long)count;
            break;
        }
    }
    return found ? 0 : -1;
}

int compare_spp_apply(struct job *j, struct ydoc *d, yaml_node_t *v, struct err *e)
{
    long spp, below, above;
    double t;
    if (yget_long(d, v, "spp", 1, SAMPLER_MAX_POINTS, &spp, e) < 0)
        return -1;
    if (compare_spp_threshold(j->spec.pixel.kind, spp, &t, &below, &above) < 0) {
        const char *rule = sampler_count_rule(j->spec.pixel.kind);
        char near[64] = "none";
        if (below && above)
            snprintf(near, sizeof near, "%ld or %ld", below, above);
        else if (below || above)
            snprintf(near, sizeof near, "%ld", below ? below : above);
        return ydoc_fail(d, v, e, "spp: %ld: %s sets hold %s (n = floor(100 / threshold)): %s, not %ld", spp,
                         sampler_kind_name(j->spec.pixel.kind), rule, near, spp);
    }
    j->spec.pixel.threshold = t;
    job_mark(j, "threshold", v);
    return 0;
}
