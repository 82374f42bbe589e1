/* report_spectrum: the error spectra's plot. */
#include "report_spectrum.h"

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

char *report_spectrum_svg(const struct verdict_study *s)
{
    int n_series = 0, any = 0;
    for (int i = 0; i < s->n_scenes; i++)
        n_series += s->scenes[i].n_variants, any |= measured(&s->scenes[i]);
    if (!any)
        return NULL;
    struct chart_series *ser = calloc((size_t)n_series + 1, sizeof *ser);
    struct chart_panel *pan = calloc((size_t)s->n_scenes + 1, sizeof *pan);
    char(*titles)[160] = calloc((size_t)s->n_scenes + 1, sizeof *titles), title[256], *svg = NULL;
    double freq[VERDICT_SPEC_RINGS];
    if (!ser || !pan || !titles)
        goto done;
    for (int r = 0; r < VERDICT_SPEC_RINGS; r++)
        freq[r] = (r + 0.5) / VERDICT_SPEC_RINGS;
    struct chart_series *sr = ser;
    for (int i = 0; i < s->n_scenes; i++) {
        const struct verdict_scene *v = &s->scenes[i];
        for (int k = 0; k < v->n_variants; k++) {
            int p = v->look.point && measured(v) ? v->look.point[k] : 0;
            size_t o = ((size_t)k * v->n_points + p) * VERDICT_SPEC_RINGS;
            sr[k] = (struct chart_series){v->variants[k],
                                          measured(v) ? VERDICT_SPEC_RINGS : 0,
                                          freq,
                                          v->spec ? v->spec + o : NULL,
                                          v->spec_lo ? v->spec_lo + o : NULL,
                                          v->spec_hi ? v->spec_hi + o : NULL};
        }
        snprintf(titles[i], sizeof titles[i], "%s: error power spectrum", v->scene);
        pan[i] = (struct chart_panel){titles[i],
                                      "frequency (1: Nyquist; log)",
                                      "power over the mean (1: white noise; log)",
                                      "no error spectrum measured",
                                      sr,
                                      v->n_variants,
                                      NULL,
                                      0,
                                      "whisker: +- one standard deviation over seeds"};
        sr += v->n_variants;
    }
    snprintf(title, sizeof title,
             "%s: radially averaged error power spectrum where the error's look is judged (geometric mean "
             "over seeds)",
             s->name);
    svg = chart_svg(title, pan, s->n_scenes, 2);
done:
    free(ser), free(pan), free(titles);
    return svg;
}
