/* report_look: the plots of how a study's error looks (error_lowfreq, the error's spectrum). */
#include "report_look.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "chart.h"

/* Whether scene v has a spectrum measured anywhere. */
static int measured(const struct verdict_scene *v)
{
    for (int i = 0; v->spec && i < v->n_variants * v->n_points * VERDICT_SPEC_RINGS; i++)
        if (isfinite(v->spec[i]))
            return 1;
    return 0;
}

/* Variant k's error_lowfreq against relMSE along the sweep; lo and hi (its whiskers) filled. */
static struct chart_series lowfreq_series(const struct verdict_scene *v, int k, double *lo, double *hi)
{
    int o = k * v->n_points, whisk = v->n_seeds > 1;
    for (int p = 0; p < v->n_points; p++) {
        lo[o + p] = v->look.mean[o + p] - v->look.se[o + p];
        hi[o + p] = v->look.mean[o + p] + v->look.se[o + p];
    }
    return (struct chart_series){v->variants[k],   v->n_points,           v->look.rel + o,
                                 v->look.mean + o, whisk ? lo + o : NULL, whisk ? hi + o : NULL};
}

/* Variant k's error spectrum at its point where the look is judged, against freq. */
static struct chart_series spectrum_series(const struct verdict_scene *v, int k, const double *freq)
{
    int p = v->look.point && measured(v) ? v->look.point[k] : 0;
    size_t o = ((size_t)k * v->n_points + p) * VERDICT_SPEC_RINGS;
    return (struct chart_series){v->variants[k],
                                 measured(v) ? VERDICT_SPEC_RINGS : 0,
                                 freq,
                                 v->spec ? v->spec + o : NULL,
                                 v->spec_lo ? v->spec_lo + o : NULL,
                                 v->spec_hi ? v->spec_hi + o : NULL};
}

char *report_look_svg(const struct verdict_study *s, enum report_look plot)
{
    /* each panel's title after its scene's name, its axes, empty note and whiskers; the plot's title */
    static const char *const words[][6] = {
        {"how the error looks", "relMSE (log)", "error_lowfreq (1: white noise; lower: bluer; log)",
         "no error_lowfreq measured", "whisker: +- one standard error",
         "error_lowfreq against relMSE along the sweep (mean over seeds; whiskers: +- one standard error)"},
        {"error power spectrum", "frequency (1: Nyquist; log)", "power over the mean (1: white noise; log)",
         "no error spectrum measured", "whisker: +- one standard deviation over seeds",
         "radially averaged error power spectrum where the error's look is judged (geometric mean over "
         "seeds)"}};
    const char *const *w = words[plot];
    int n_series = 0, n_vals = 0, any = plot != REPORT_LOOK_SPECTRUM;
    for (int i = 0; i < s->n_scenes; i++) {
        n_series += s->scenes[i].n_variants;
        n_vals += s->scenes[i].n_variants * s->scenes[i].n_points;
        any |= measured(&s->scenes[i]);
    }
    if (!any)
        return NULL;
    struct chart_series *ser = calloc((size_t)n_series + 1, sizeof *ser);
    struct chart_panel *pan = calloc((size_t)s->n_scenes + 1, sizeof *pan);
    double *mem = calloc((size_t)n_vals * 2 + 1, sizeof *mem), freq[VERDICT_SPEC_RINGS];
    char(*titles)[160] = calloc((size_t)s->n_scenes + 1, sizeof *titles), title[256], *svg = NULL;
    if (!ser || !pan || !mem || !titles)
        goto done;
    for (int r = 0; r < VERDICT_SPEC_RINGS; r++)
        freq[r] = (r + 0.5) / VERDICT_SPEC_RINGS;
    struct chart_series *sr = ser;
    double *lo = mem, *hi = mem + n_vals;
    for (int i = 0; i < s->n_scenes; i++) {
        const struct verdict_scene *v = &s->scenes[i];
        for (int k = 0; k < v->n_variants; k++)
            sr[k] = plot == REPORT_LOOK_SPECTRUM ? spectrum_series(v, k, freq) : lowfreq_series(v, k, lo, hi);
        snprintf(titles[i], sizeof titles[i], "%s: %s", v->scene, w[0]);
        pan[i] = (struct chart_panel){titles[i], w[1], w[2], w[3], sr, v->n_variants, NULL, 0, w[4]};
        sr += v->n_variants;
        lo += v->n_variants * v->n_points;
        hi += v->n_variants * v->n_points;
    }
    snprintf(title, sizeof title, "%s: %s", s->name, w[5]);
    svg = chart_svg(title, pan, s->n_scenes, 2);
done:
    free(ser), free(pan), free(mem), free(titles);
    return svg;
}
