/* report_chart: a compare job's chart.svg from its figures. */
#include "report_chart.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "chart.h"
#include "study/judge/compare_stats.h"

char *report_chart_svg(const struct compare *c)
{
    int ns = c->n_variants, np = c->n_points, nsc = c->n_scenes;
    size_t per = (size_t)nsc * ns * np;
    double *mem = calloc(per * 5, sizeof *mem);
    int *order = calloc((size_t)np, sizeof *order);
    struct chart_series *ser = calloc((size_t)nsc * ns * 2, sizeof *ser);
    struct chart_panel *pan = calloc((size_t)nsc * 2, sizeof *pan);
    char(*titles)[160] = calloc((size_t)nsc * 2, sizeof *titles);
    static const double slopes[] = {-1, -1.5};
    char *svg = NULL, title[400];
    if (!mem || !order || !ser || !pan || !titles)
        goto done;
    double *cpu = mem, *spp = mem + per, *rel = mem + 2 * per, *lo = mem + 3 * per, *hi = mem + 4 * per;
    for (int s = 0; s < nsc; s++) {
        struct chart_series *by_time = ser + (size_t)2 * s * ns, *by_spp = by_time + ns;
        /* the verdict's figures (one statistic throughout): geometric means with 95% intervals */
        const struct verdict_scene *vs =
            c->has_verdict && s < c->verdict.n_scenes ? &c->verdict.scenes[s] : NULL;
        int judged = vs && vs->point_rel && vs->cost;
        for (int v = 0; v < ns; v++) {
            size_t k0 = ((size_t)s * ns + v) * np;
            compare_stats_point_order(c, s, v, order);
            for (int i = 0; i < np; i++) {
                struct compare_agg a;
                compare_stats_aggregate(c, s, v, order[i], &a);
                size_t k = k0 + i, vp = (size_t)v * np + order[i];
                spp[k] = a.spp;
                cpu[k] = judged ? vs->cost[vp] : a.cpu_s;
                rel[k] = judged ? vs->point_rel[vp] : a.rel;
                lo[k] = judged ? vs->point_rel_lo[vp] : NAN, hi[k] = judged ? vs->point_rel_hi[vp] : NAN;
            }
            /* One seed has no spread: a whisker would be a dot claiming one. */
            int whisk = judged && c->n_seeds > 1;
            const double *l = whisk ? lo + k0 : NULL, *h = whisk ? hi + k0 : NULL;
            by_time[v] = (struct chart_series){c->variants[v], np, cpu + k0, rel + k0, l, h};
            by_spp[v] = (struct chart_series){c->variants[v], np, spp + k0, rel + k0, l, h};
        }
        const char *note =
            c->scenes[s].ref_kind == COMPARE_REF_NONE ? "no reference given: no error to chart" : NULL;
        for (int k = 0; k < 2; k++) { /* against CPU time, then against samples */
            snprintf(titles[2 * s + k], sizeof titles[0], "%s: error against %s", c->scenes[s].name,
                     k ? "samples" : "CPU time");
            pan[2 * s + k] =
                (struct chart_panel){titles[2 * s + k],
                                     k ? "samples per pixel (mean, log)" : "CPU time per image (s, log)",
                                     "relMSE (eps 0.01, log)",
                                     note,
                                     k ? by_spp : by_time,
                                     ns,
                                     slopes,
                                     2,
                                     "whisker: 95% CI"};
        }
    }
    if (c->n_seeds > 1)
        snprintf(title, sizeof title,
                 "%s: relMSE against CPU time and samples per pixel (per point the geometric mean over %d "
                 "seeds, the reference's noise taken out; whiskers: its 95%% confidence interval; CPU time: "
                 "the cost design's per image)",
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
