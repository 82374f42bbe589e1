/* verdict_spectrum: the error's spectrum per (variant, point) and the `structured` failure. */
#include "verdict_spectrum.h"

#include <math.h>
#include <stdlib.h>

#include "image/errspec.h"
#include "verdict_say.h"

_Static_assert(VERDICT_SPEC_RINGS == ERRSPEC_RINGS, "the model's rings are errspec's");

/* The seeds' mean and standard deviation of (v, p, ring)'s log10 power into out's spec arrays. */
static void ring_band(const struct verdict_figures *f, int v, int p, int r, struct verdict_scene *out)
{
    double s = 0, ss = 0;
    int m = 0;
    for (int k = 0; k < f->n_seeds; k++) {
        double y = f->spec_ring[((size_t)verdict_at(f, v, p, k)) * VERDICT_SPEC_RINGS + r];
        if (isfinite(y))
            s += y, ss += y * y, m++;
    }
    size_t i = ((size_t)v * f->n_points + p) * VERDICT_SPEC_RINGS + r;
    double mean = m ? s / m : NAN, sd = m > 1 ? sqrt(fmax(0, (ss - m * mean * mean) / (m - 1))) : 0;
    out->spec[i] = pow(10, mean), out->spec_lo[i] = pow(10, mean - sd), out->spec_hi[i] = pow(10, mean + sd);
}

int verdict_spectrum_compute(const struct verdict_figures *f, struct verdict_scene *out)
{
    size_t per = (size_t)f->n_variants * f->n_points;
    out->spec = calloc(per * VERDICT_SPEC_RINGS, sizeof *out->spec);
    out->spec_lo = calloc(per * VERDICT_SPEC_RINGS, sizeof *out->spec_lo);
    out->spec_hi = calloc(per * VERDICT_SPEC_RINGS, sizeof *out->spec_hi);
    out->spec_peak_p = calloc(per, sizeof *out->spec_peak_p),
    out->spec_aniso = calloc(per, sizeof *out->spec_aniso);
    if (!out->spec || !out->spec_lo || !out->spec_hi || !out->spec_peak_p || !out->spec_aniso)
        return -1;
    for (size_t i = 0; i < per * VERDICT_SPEC_RINGS; i++)
        out->spec[i] = out->spec_lo[i] = out->spec_hi[i] = NAN;
    for (size_t i = 0; i < per; i++) {
        out->spec_peak_p[i] = f->spec_peak_p ? f->spec_peak_p[i] : NAN;
        out->spec_aniso[i] = f->spec_aniso ? f->spec_aniso[i] : NAN;
    }
    for (int v = 0; v < f->n_variants; v++) {
        for (int p = 0; p < f->n_points && f->spec_ring; p++)
            for (int r = 0; r < VERDICT_SPEC_RINGS; r++)
                ring_band(f, v, p, r, out);
        /* each point is judged; the peak's bound shares ERRSPEC_PEAK_P among them (Bonferroni) */
        int at = -1;
        double least = INFINITY, aniso = NAN;
        for (int p = 0; p < f->n_points; p++) {
            double pp = out->spec_peak_p[v * f->n_points + p], an = out->spec_aniso[v * f->n_points + p];
            int flagged = pp * f->n_points < ERRSPEC_PEAK_P || an > ERRSPEC_ANISOTROPY;
            if (flagged && (at < 0 || pp < least))
                at = p, least = pp, aniso = an;
        }
        if (at < 0)
            continue;
        verdict_say_failure(f, out, VERDICT_PATTERN, v, at, least, aniso);
    }
    return 0;
}
