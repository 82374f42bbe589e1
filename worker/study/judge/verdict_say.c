/* verdict_say: the words of a scene's verdict. */
#include "verdict_say.h"

#include "verdict_rank.h"
#include "sample/sampler_kind.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Append printf text to buf (of VERDICT_TEXT_MAX bytes), truncating. */
static void __attribute__((format(printf, 2, 3))) append(char *buf, const char *fmt, ...)
{
    size_t len = strlen(buf);
    if (len + 1 >= VERDICT_TEXT_MAX)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf + len, VERDICT_TEXT_MAX - len, fmt, ap);
    va_end(ap);
}

static char *next_line(char (*lines)[VERDICT_TEXT_MAX], int *n)
{
    if (*n >= VERDICT_SAY_MAX)
        return NULL;
    lines[*n][0] = 0;
    return lines[(*n)++];
}

static const char *point_name(const struct verdict_figures *f, int p)
{
    return p >= 0 && p < f->n_points && f->points ? f->points[p] : "every point";
}

void verdict_say_failure(const struct verdict_figures *f, struct verdict_scene *out,
                         enum verdict_failure_kind kind, int variant, int p, double value, double detail)
{
    struct verdict_failure *x = &out->failures[out->n_failures++];
    *x = (struct verdict_failure){
        .kind = kind, .variant = variant, .point = p, .value = value, .detail = detail};
    const char *v = f->variants[variant], *at = point_name(f, p);
    switch (x->kind) {
    case VERDICT_STRUCTURED:
        append(x->text, "%s: %.0f%% of its error at %s repeats in every seed", v, 100 * x->value, at);
        if (isfinite(x->detail))
            append(x->text, " (%.0f%% a bias in mean radiance, %.0f%% a pattern: aliasing or structure)",
                   100 * x->detail, 100 * (x->value - x->detail));
        else
            append(x->text, " (aliasing, a pattern or a bias)");
        break;
    case VERDICT_BIASED:
        append(x->text,
               "%s: biased: its seeds' mean radiance at %s is %+.2f%% off the reference's (%.1f standard "
               "errors)",
               v, at, x->value, x->detail);
        break;
    case VERDICT_HEAVY_TAILED:
        append(x->text,
               "%s: fireflies: its seeds' relMSE at %s span a factor %.3g (the worst %.0f%% of their sum): "
               "its mean and standard error mean little, so no bias or stall is judged",
               v, at, x->value, 100 * x->detail);
        break;
    case VERDICT_PATTERN:
        append(x->text,
               "%s: structured: its seeds' error spectrum at %s has a peak noise gives with chance under "
               "%.2g, anisotropy %.2f (a pattern, not noise: never called bluest)",
               v, at, x->value, x->detail);
        break;
    case VERDICT_STALLS:
        append(x->text, "%s: error stops falling at %s (local slope %.2f against samples)", v, at, x->value);
        break;
    case VERDICT_NONFINITE:
        append(x->text, "%s: %.0f non-finite samples dropped", v, x->value);
        break;
    case VERDICT_SHARE:
        append(x->text, "%s: drawing its point sets takes %.0f%% of its CPU time at %s", v, 100 * x->value,
               at);
        break;
    }
}

static const char *ranking_name(const struct verdict_scene *out, const struct verdict_ranking *r)
{
    return r == &out->by_cpu ? "at equal CPU time" : r == &out->by_samples ? "at equal samples" : "by slope";
}

/* The labels of the variants of rank `rank` in r, joined: "jitter, sobol". */
static void group(const struct verdict_scene *out, const struct verdict_ranking *r, int rank, char *buf)
{
    int shown = 0;
    buf[0] = 0;
    for (int i = 0; i < r->n; i++)
        if (r->e[i].rank == rank)
            append(buf, "%s%s", shown++ ? ", " : "", out->variants[r->e[i].variant]);
}

/* Whether any image of f was scored (a study without a reference scores none). */
static int scored(const struct verdict_figures *f)
{
    for (int i = 0; i < f->n_variants * f->n_points * f->n_seeds; i++)
        if (isfinite(f->relmse[i]))
            return 1;
    return 0;
}

void verdict_say_warnings(const struct verdict_figures *f, struct verdict_scene *out)
{
    char *w;
    if (!scored(f) && (w = next_line(out->warnings, &out->n_warnings)))
        append(w, "no reference: no image has an error to rank by, so nothing is ranked (give the study a "
                  "reference:, settings or an image)");
    if (f->n_seeds < 2 && (w = next_line(out->warnings, &out->n_warnings)))
        append(w, "one seed: no spread across seeds to judge a difference by, so nothing is ranked");
    if (out->cost_from_images && scored(f) && (w = next_line(out->warnings, &out->n_warnings)))
        append(w, "no cost design measured (no cost.csv): equal CPU time is judged by each image's own CPU "
                  "time, seed k as block k, which a busy machine can tilt");
    double densest = 0;
    for (int i = 0; i < f->n_variants * f->n_points * f->n_seeds; i++)
        densest = fmax(densest, f->spp[i]);
    if (f->ref.spp > 0 && f->ref.spp < VERDICT_REF_FACTOR * densest &&
        (w = next_line(out->warnings, &out->n_warnings)))
        append(w,
               "the reference has %.0f samples per pixel, fewer than %dx the densest point's %.0f: its own "
               "noise is a large part of the error measured there%s",
               f->ref.spp, VERDICT_REF_FACTOR, densest,
               f->ref_noise_refused ? ", and too sparse to take out (its halves miss the pixels where both "
                                      "agree by chance): every relMSE shown includes it"
                                    : "");
    int floored = 0, scoredn = 0;
    for (int i = 0; i < f->n_variants * f->n_points * f->n_seeds && f->ref.relmse > 0; i++)
        if (isfinite(f->relmse[i]))
            scoredn++, floored += f->relmse[i] - f->ref.relmse < 0.01 * f->relmse[i];
    if (floored && (w = next_line(out->warnings, &out->n_warnings)))
        append(
            w,
            "%d of %d images' relMSE are within the reference's own %.3g: their own error is shown as 1%% of "
            "the measured (the difference cannot be told from the reference's noise)",
            floored, scoredn, f->ref.relmse);
    if ((f->reference_unread || f->images_unread) && (w = next_line(out->warnings, &out->n_warnings)))
        append(w,
               "skipped: the share of the error that repeats in every seed, its split into bias and pattern, "
               "and the bias check %s (%s)",
               f->reference_unread ? "everywhere" : "where images are missing",
               f->reference_unread ? "the reference image could not be read"
                                   : "some seed images could not be read");
    for (int v = 0; v < f->n_variants && f->ref.relmse > 0; v++) {
        char near[VERDICT_TEXT_MAX] = "";
        for (int p = 0; p < f->n_points; p++) {
            double mean = verdict_mean(f, f->relmse, v, p);
            if (mean < VERDICT_REF_NOISE * f->ref.relmse)
                append(near, "%s%s (%.3g)", near[0] ? ", " : "", point_name(f, p), mean);
        }
        if (near[0] && (w = next_line(out->warnings, &out->n_warnings)))
            append(
                w,
                "%s's relMSE is within %dx of the reference's own %.3g at %s: the reference's noise is most "
                "of it there (it is subtracted; a denser reference would tell more)",
                f->variants[v], VERDICT_REF_NOISE, f->ref.relmse, near);
    }
    const struct verdict_ranking *rs[] = {&out->by_samples, &out->by_cpu, &out->by_slope};
    for (int i = 0; i < 3 && f->n_seeds > 1; i++) {
        const struct verdict_ranking *r = rs[i];
        char top[VERDICT_TEXT_MAX];
        group(out, r, 1, top);
        if (r->n > 1 && r->status != VERDICT_CLEAR && (w = next_line(out->warnings, &out->n_warnings)))
            append(w, "%s, %s are not told apart by their seeds%s (%s, Holm-corrected, alpha %.2g): %s",
                   ranking_name(out, r), top, r->pair_p ? " and cost blocks" : "",
                   r->pair_p ? "a t test with both uncertainties" : "Welch's t test", VERDICT_ALPHA,
                   r->status == VERDICT_TIE ? "tied, no single winner" : "inconclusive");
        for (int j = 0; j < r->n; j++)
            if (r->e[j].untold && !isfinite(r->at))
                continue; /* nothing measured (no reference): no time to read at */
            else if (r->e[j].untold && (w = next_line(out->warnings, &out->n_warnings)))
                append(w,
                       "%s, the study cannot tell where %s stands: %.3g CPU seconds lie too far below its "
                       "points for its error-against-time line to reach (it is separated from none)",
                       ranking_name(out, r), out->variants[r->e[j].variant], r->at);
            else if (r->e[j].extrapolated && (w = next_line(out->warnings, &out->n_warnings)))
                append(w,
                       "%s, %s is read at %.3g CPU seconds along its error-against-time line beyond its "
                       "cheapest point (the extrapolation's uncertainty is in its interval)",
                       ranking_name(out, r), out->variants[r->e[j].variant], r->at);
            else if (r->e[j].unreached && (w = next_line(out->warnings, &out->n_warnings)))
                append(w,
                       "%s, %s cannot be had: its cheapest image costs far more than the %.3g %s every other "
                       "variant reached, so it ranks behind them",
                       ranking_name(out, r), out->variants[r->e[j].variant], r->at,
                       r == &out->by_cpu ? "CPU seconds" : "samples per pixel");
    }
}

/* "At equal CPU time (0.21 s per image), use jitter: ..." for one ranking. */
static void say_ranking(const struct verdict_scene *out, const struct verdict_ranking *r, const char *at,
                        int scored, char *s)
{
    char top[VERDICT_TEXT_MAX], rest[VERDICT_TEXT_MAX];
    if (r->n < 2)
        return;
    if (r->status == VERDICT_INCONCLUSIVE) {
        append(s, "%s on %s, no two variants are told apart by their seeds%s: inconclusive", at, out->scene,
               r->pair_p ? " and cost blocks" : "");
        append(s, !scored            ? " (no reference: no error to compare)."
                  : out->n_seeds < 2 ? " (one seed)."
                                     : " (more seeds or samples would tell).");
        return;
    }
    group(out, r, 1, top);
    const struct verdict_entry *b = &r->e[0], *next = NULL;
    for (int i = 1; i < r->n && !next; i++)
        if (r->e[i].rank > 1)
            next = &r->e[i];
    if (r->status == VERDICT_CLEAR)
        append(s, "%s on %s, use %s: relMSE %.3g, %.2fx lower than the next, %s.", at, out->scene, top,
               b->value, next->value / b->value, out->variants[next->variant]);
    else {
        group(out, r, next->rank, rest);
        append(s, "%s on %s, %s tie (not told apart by their seeds%s), ahead of %s.", at, out->scene, top,
               r->pair_p ? " and cost blocks" : "", rest);
    }
    for (int i = 0; i < out->n_failures; i++) /* a low error now, but not the reference's picture */
        if (out->failures[i].kind == VERDICT_BIASED && verdict_entry_of(r, out->failures[i].variant) &&
            verdict_entry_of(r, out->failures[i].variant)->rank == 1)
            append(s,
                   " But %s is biased (%+.2f%% in mean radiance): more samples will not bring it to the "
                   "reference.",
                   out->variants[out->failures[i].variant], out->failures[i].value);
}

static void say_slopes(const struct verdict_scene *out, char *s)
{
    const struct verdict_ranking *r = &out->by_slope;
    if (r->n < 2 || r->status == VERDICT_INCONCLUSIVE)
        return;
    char top[VERDICT_TEXT_MAX];
    group(out, r, 1, top);
    const struct verdict_entry *b = &r->e[0], *w = &r->e[r->n - 1];
    append(
        s,
        "Error falls fastest with %s (relMSE ~ spp^%.2f, 95%% CI %.2f to %.2f) and slowest with %s (%.2f).",
        top, b->value, b->lo, b->hi, out->variants[w->variant], w->value);
}

/* CPU seconds per sample at v's densest point: the cost design's per image over its seeds' mean
   samples per pixel (the pixels cancel in a ratio). */
static double per_sample(const struct verdict_figures *f, const struct verdict_scene *out, int v)
{
    double best = 0, cost = NAN;
    for (int p = 0; p < f->n_points; p++) {
        double spp = 0;
        for (int k = 0; k < f->n_seeds; k++)
            spp += f->spp[verdict_at(f, v, p, k)];
        if (spp > best)
            best = spp, cost = out->cost[v * f->n_points + p] / (spp / f->n_seeds);
    }
    return cost;
}

/* Whether variant v's pixel sampler's row carries flag (sample/sampler_kind.h). */
static int has(const struct verdict_figures *f, int v, enum sampler_flag flag)
{
    enum sampler_kind k;
    return sampler_kind_parse(f->samplers[v], &k) == 0 && sampler_kind_has(k, flag);
}

/* What Bridson's fresh sets cost against jitter per sample, and against the pool at equal time. */
static void say_poisson(const struct verdict_figures *f, struct verdict_scene *out, int v)
{
    char *s;
    for (int j = 0; j < f->n_variants; j++) {
        if (has(f, j, SAMPLER_BASELINE) && (s = next_line(out->sentences, &out->n_sentences))) {
            const struct verdict_entry *a = verdict_entry_of(&out->by_samples, v),
                                       *b = verdict_entry_of(&out->by_samples, j);
            append(s, "On %s, %s costs %.1fx %s's CPU time per sample and buys ", out->scene, f->variants[v],
                   per_sample(f, out, v) / per_sample(f, out, j), f->variants[j]);
            if (verdict_beats(&out->by_samples, a, b))
                append(s, "%.2fx lower relMSE at equal samples.", b->value / a->value);
            else if (verdict_beats(&out->by_samples, b, a))
                append(s, "nothing at equal samples (its relMSE is %.2fx %s's).", a->value / b->value,
                       f->variants[j]);
            else
                append(s, "nothing measurable at equal samples (not told apart by the seeds).");
            break;
        }
    }
    for (int u = 0; u < f->n_variants; u++) {
        if (!has(f, u, SAMPLER_POOLED) || f->pools[u] == 0 ||
            !(s = next_line(out->sentences, &out->n_sentences)))
            continue;
        const struct verdict_entry *a = verdict_entry_of(&out->by_cpu, u),
                                   *b = verdict_entry_of(&out->by_cpu, v);
        int pool = verdict_beats(&out->by_cpu, a, b), fresh = verdict_beats(&out->by_cpu, b, a);
        if (pool && b->extrapolated)
            append(s,
                   "At equal CPU time on %s, %s (the pool) beats %s (fresh sets), whose cheapest image costs "
                   "more than the %.3g s the variants are compared at (read along its error-time line).",
                   out->scene, f->variants[u], f->variants[v], out->by_cpu.at);
        else if (pool || fresh)
            append(s, "At equal CPU time on %s, %s (%s) beats %s (%s): relMSE %.3g against %.3g.", out->scene,
                   f->variants[pool ? u : v], pool ? "the pool" : "fresh sets", f->variants[pool ? v : u],
                   pool ? "fresh sets" : "the pool", fmin(a->value, b->value), fmax(a->value, b->value));
        else
            append(s,
                   "At equal CPU time on %s, the pool %s and the fresh sets %s tie (not told apart by their "
                   "seeds).",
                   out->scene, f->variants[u], f->variants[v]);
    }
}

void verdict_say_sentences(const struct verdict_figures *f, struct verdict_scene *out)
{
    char *s;
    const int any = scored(f);
    const struct verdict_ranking *rs[] = {&out->by_cpu, &out->by_samples};
    char when[2][96];
    snprintf(when[0], sizeof when[0], "At equal CPU time (%.3g s per image)", out->by_cpu.at);
    snprintf(when[1], sizeof when[1], "At equal samples (%.0f per pixel)", out->by_samples.at);
    for (int i = 0; i < 2 && (s = next_line(out->sentences, &out->n_sentences)); i++)
        say_ranking(out, rs[i], when[i], any, s);
    if ((s = next_line(out->sentences, &out->n_sentences)))
        say_slopes(out, s);
    for (int i = 0; i < out->n_failures; i++) {
        const struct verdict_failure *x = &out->failures[i];
        const char *v = f->variants[x->variant], *at = point_name(f, x->point);
        if (x->kind == VERDICT_SHARE || !(s = next_line(out->sentences, &out->n_sentences)))
            continue; /* the sampler's share is said with Poisson's cost */
        if (x->kind == VERDICT_STRUCTURED)
            append(s,
                   "%s %s on %s: %.0f%% of its error at %s repeats in every seed, so no number of seeds "
                   "averages it away.",
                   v, has(f, x->variant, SAMPLER_ALIASES) ? "aliases" : "has structured error", out->scene,
                   100 * x->value, at);
        else if (x->kind == VERDICT_BIASED)
            append(
                s,
                "%s is biased on %s: its mean radiance at %s is %+.2f%% off the reference's (%.1f standard "
                "errors), so more samples or seeds will not bring it to the reference.",
                v, out->scene, at, x->value, x->detail);
        else if (x->kind == VERDICT_PATTERN)
            append(
                s,
                "%s's error on %s is structured at %s: its spectrum has a peak or a direction noise does "
                "not (chance under %.2g, anisotropy %.2f), so however low its error_lowfreq it is not blue "
                "noise.",
                v, out->scene, at, x->value, x->detail);
        else if (x->kind == VERDICT_HEAVY_TAILED)
            append(s,
                   "%s has fireflies on %s: at %s its seeds' relMSE span a factor %.3g, so rare, "
                   "huge samples decide its mean error, and neither a bias nor a stall can be judged.",
                   v, out->scene, at, x->value);
        else if (x->kind == VERDICT_STALLS)
            append(s,
                   "%s's error stops falling at %s on %s (local slope %.2f): more samples buy little there.",
                   v, at, out->scene, x->value);
        else
            append(s, "%s dropped %.0f non-finite samples on %s.", v, x->value, out->scene);
    }
    for (int v = 0; v < f->n_variants; v++)
        if (has(f, v, SAMPLER_POOLED) && f->pools[v] == 0)
            say_poisson(f, out, v);
    int kept = 0; /* a ranking with fewer than two variants said nothing */
    for (int i = 0; i < out->n_sentences; i++)
        if (out->sentences[i][0])
            memmove(out->sentences[kept++], out->sentences[i], VERDICT_TEXT_MAX);
    out->n_sentences = kept;
}
