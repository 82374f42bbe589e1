/* verdict_look: error_lowfreq per variant and point, and the bluest variant at equal relMSE. */
#include "verdict_look.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "verdict_rank.h"

/* Per (variant, point): error_lowfreq's mean and SE, relMSE's geometric mean. */
static void per_point(const struct verdict_figures *f, struct verdict_look *l)
{
    for (int v = 0; v < f->n_variants; v++)
        for (int p = 0; p < f->n_points; p++) {
            struct verdict_entry lf, r;
            verdict_entry_start(&lf, v), verdict_entry_start(&r, v);
            for (int k = 0; k < f->n_seeds; k++) {
                int i = verdict_at(f, v, p, k);
                verdict_entry_add(&lf, f->lowfreq ? f->lowfreq[i] : NAN, 0);
                verdict_entry_add(&r, verdict_rel(f, i), 1);
            }
            verdict_entry_end(&lf, 0), verdict_entry_end(&r, 1);
            int vp = v * f->n_points + p;
            l->mean[vp] = lf.value, l->se[vp] = lf.se, l->rel[vp] = r.value;
        }
}

/* The sparsest samples per pixel every variant has, and each variant's point nearest it. */
static void common_point(const struct verdict_figures *f, struct verdict_look *l)
{
    double at = 0;
    for (int v = 0; v < f->n_variants; v++) {
        double lo = INFINITY;
        for (int p = 0; p < f->n_points; p++)
            lo = fmin(lo, verdict_mean(f, f->spp, v, p));
        at = fmax(at, lo);
    }
    l->at = at > 0 && isfinite(at) ? at : NAN;
    for (int v = 0; v < f->n_variants && isfinite(l->at); v++)
        for (int p = 1; p < f->n_points; p++)
            if (fabs(log(verdict_mean(f, f->spp, v, p) / at)) <
                fabs(log(verdict_mean(f, f->spp, v, l->point[v]) / at)))
                l->point[v] = p;
}

static void say(const struct verdict_scene *out, const struct verdict_look *l, char *buf, size_t n)
{
    char winner[256];
    size_t len = (size_t)snprintf(buf, n,
                                  "How the error looks at %.3g sample%s per pixel (error_lowfreq: 1 is white "
                                  "noise, lower is bluer), among the variants equal in relMSE there:",
                                  l->at, l->at == 1 ? "" : "s");
    for (int i = 0; i < l->by_look.n && len < n; i++) {
        const struct verdict_entry *e = &l->by_look.e[i];
        len += (size_t)snprintf(buf + len, n - len, "%s %s %.2f +- %.2f", i ? "," : "",
                                out->variants[e->variant], e->value, e->se);
    }
    verdict_ranking_winner(out, &l->by_look, 1, winner, sizeof winner);
    if (len < n)
        snprintf(buf + len, n - len, "; bluest: %s.", winner);
}

int verdict_look_compute(const struct verdict_figures *f, struct verdict_scene *out)
{
    struct verdict_look *l = &out->look;
    int nv = f->n_variants;
    size_t per = (size_t)nv * f->n_points;
    *l = (struct verdict_look){.at = NAN};
    l->point = calloc((size_t)nv, sizeof *l->point);
    l->mean = calloc(per, sizeof *l->mean), l->se = calloc(per, sizeof *l->se);
    l->rel = calloc(per, sizeof *l->rel);
    l->by_relmse.e = calloc((size_t)nv, sizeof *l->by_relmse.e);
    l->by_look.e = calloc((size_t)nv, sizeof *l->by_look.e);
    if (!l->point || !l->mean || !l->se || !l->rel || !l->by_relmse.e || !l->by_look.e) {
        verdict_look_free(l);
        return -1;
    }
    per_point(f, l);
    common_point(f, l);
    if (!f->lowfreq || !isfinite(l->at))
        return 0;
    l->by_relmse = (struct verdict_ranking){.at = l->at, .n = nv, .e = l->by_relmse.e};
    for (int v = 0; v < nv; v++) {
        verdict_entry_start(&l->by_relmse.e[v], v);
        for (int k = 0; k < f->n_seeds; k++)
            verdict_entry_add(&l->by_relmse.e[v], verdict_rel(f, verdict_at(f, v, l->point[v], k)), 1);
        verdict_entry_end(&l->by_relmse.e[v], 1);
    }
    verdict_rank(&l->by_relmse);
    l->by_look = (struct verdict_ranking){.at = l->at, .e = l->by_look.e};
    for (int i = 0; i < nv; i++) {
        const struct verdict_entry *r = &l->by_relmse.e[i];
        struct verdict_entry *e = &l->by_look.e[l->by_look.n];
        if (r->rank != 1 || !(r->n > 0) || verdict_failure_of(out, r->variant, VERDICT_PATTERN))
            continue; /* a pattern is not blue noise however little of it is at low frequencies */
        verdict_entry_start(e, r->variant);
        for (int k = 0; k < f->n_seeds; k++)
            verdict_entry_add(e, f->lowfreq[verdict_at(f, r->variant, l->point[r->variant], k)], 0);
        verdict_entry_end(e, 0);
        l->by_look.n += e->n > 0;
    }
    if (l->by_look.n > 0)
        verdict_rank(&l->by_look);
    if (l->by_look.n > 1 && out->n_sentences < VERDICT_SAY_MAX) {
        say(out, l, out->sentences[out->n_sentences], sizeof out->sentences[0]);
        out->n_sentences++;
    }
    return 0;
}
