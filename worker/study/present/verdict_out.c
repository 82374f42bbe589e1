/* verdict_out: the verdict as verdict.json, as the report's opening HTML, and as the stderr
   summary. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "report_look.h"
#include "verdict_out.h"
#include "study/judge/verdict_rank.h"
#include "study/load/html_text.h"

#define TIE_RULE                                                                                             \
    "Each variant's figure is its seeds' mean of log relMSE at the common point (for slopes: the mean of "   \
    "its per-seed log-log fits), with its standard error. Two variants are ranked apart only when Welch's "  \
    "t test rejects equal means, Holm-corrected across every pair of the ranking, at alpha 0.05: the "       \
    "chance of separating any pair of truly equal variants is at most about 5%. A variant's rank is 1 + "    \
    "the number of variants ranked apart ahead of it; best first by rank, then mean. Equal samples and "     \
    "equal CPU time are each the largest that every variant reached (the smallest of the variants' "         \
    "densest points), each seed's relMSE read there in log-log between its measured points; a variant "      \
    "whose cheapest point costs over 1.25x that is not reached and ranks behind those that are. A ranking "  \
    "is clear when one variant alone ranks 1, a tie when several do but some variant is behind, "            \
    "inconclusive when none is ahead of another or there is only one seed."

static const char *status_name(enum verdict_status s)
{
    return s == VERDICT_CLEAR ? "clear" : s == VERDICT_TIE ? "tie" : "inconclusive";
}

/* A failure kind's name in verdict.json, and its detail's key there (NULL: none). */
static const char *const kind_names[][2] = {{"structured_error", "bias_share"},
                                            {"stops_falling", NULL},
                                            {"non_finite", NULL},
                                            {"sampler_share", NULL},
                                            {"biased", "standard_errors"},
                                            {"heavy_tailed", "worst_share"},
                                            {"structured", "anisotropy"}};

static void json_ranking(struct json *j, const char *key, const char *at_key, const char *value_key,
                         const struct verdict_scene *v, const struct verdict_ranking *r)
{
    char winner[256];
    json_begin_object(j, key);
    if (at_key)
        json_number(j, at_key, r->at);
    json_string(j, "status", status_name(r->status));
    verdict_ranking_winner(v, r, 0, winner, sizeof winner);
    json_string(j, "winner", winner);
    json_begin_array(j, "ranking");
    for (int i = 0; i < r->n; i++) {
        const struct verdict_entry *e = &r->e[i];
        json_begin_object(j, NULL);
        json_string(j, "variant", v->variants[e->variant]);
        json_uint(j, "rank", (uint64_t)e->rank);
        json_number(j, value_key, e->value);
        json_number(j, "standard_error", e->se);
        json_number(j, "ci95_lo", e->lo);
        json_number(j, "ci95_hi", e->hi);
        json_bool(j, "reached", !e->unreached);
        if (r->pair_p) { /* equal CPU time: read along its error-time line, or not at all */
            json_bool(j, "extrapolated", e->extrapolated);
            json_bool(j, "cannot_tell", e->untold);
        }
        json_end_object(j);
    }
    json_end_array(j);
    json_end_object(j);
}

/* "error_look": the rule's common point, each variant's error_lowfreq there and along the sweep,
   the comparison among the variants equal in relMSE, and the bluest. */
static void json_look(struct json *j, const struct verdict_scene *v)
{
    const struct verdict_look *l = &v->look;
    json_begin_object(j, "error_look");
    json_number(j, "at_samples_per_pixel", l->at);
    json_begin_array(j, "variants");
    for (int k = 0; k < v->n_variants; k++) {
        int p = l->point[k], o = k * v->n_points;
        json_begin_object(j, NULL);
        json_string(j, "variant", v->variants[k]);
        json_number(j, "error_lowfreq", l->mean[o + p]);
        json_number(j, "standard_error", l->se[o + p]);
        json_number(j, "relmse", l->rel[o + p]);
        json_begin_array(j, "along_sweep");
        for (int q = 0; q < v->n_points; q++) {
            json_begin_object(j, NULL);
            json_number(j, "error_lowfreq", l->mean[o + q]);
            json_number(j, "standard_error", l->se[o + q]);
            json_number(j, "relmse", l->rel[o + q]);
            if (v->spec_peak_p) {
                json_number(j, "spectrum_peak_p", v->spec_peak_p[o + q]);
                json_number(j, "anisotropy", v->spec_aniso[o + q]);
                json_begin_array(j, "spectrum");
                for (int r = 0; r < VERDICT_SPEC_RINGS; r++)
                    json_number(j, NULL, v->spec[(size_t)(o + q) * VERDICT_SPEC_RINGS + r]);
                json_end_array(j);
            }
            json_end_object(j);
        }
        json_end_array(j);
        json_end_object(j);
    }
    json_end_array(j);
    json_ranking(j, "equal_relmse", NULL, "relmse", v, &l->by_relmse);
    json_ranking(j, "bluest", NULL, "error_lowfreq", v, &l->by_look);
    json_end_object(j);
}

static void json_scene(struct json *j, const struct verdict_scene *v)
{
    json_begin_object(j, NULL);
    json_string(j, "scene", v->scene);
    json_uint(j, "seeds", (uint64_t)v->n_seeds);
    json_number(j, "reference_relmse", v->ref_relmse);
    json_string(j, "rank_by", v->rank_by == VERDICT_RANK_MEDIAN ? "median" : "mean");
    json_bool(j, "costs_from_images", v->cost_from_images);
    json_ranking(j, "equal_samples", "at_samples_per_pixel", "relmse", v, &v->by_samples);
    json_ranking(j, "equal_cpu_time", "at_cpu_s", "relmse", v, &v->by_cpu);
    json_ranking(j, "slopes", NULL, "slope", v, &v->by_slope);
    json_look(j, v);
    json_begin_array(j, "failures");
    for (int i = 0; i < v->n_failures; i++) {
        const struct verdict_failure *x = &v->failures[i];
        json_begin_object(j, NULL);
        json_string(j, "variant", v->variants[x->variant]);
        json_string(j, "kind", kind_names[x->kind][0]);
        json_number(j, "value", x->value);
        if (kind_names[x->kind][1])
            json_number(j, kind_names[x->kind][1], x->detail);
        json_string(j, "text", x->text);
        json_end_object(j);
    }
    json_end_array(j);
    json_begin_array(j, "warnings");
    for (int i = 0; i < v->n_warnings; i++)
        json_string(j, NULL, v->warnings[i]);
    json_end_array(j);
    json_begin_array(j, "sentences");
    for (int i = 0; i < v->n_sentences; i++)
        json_string(j, NULL, v->sentences[i]);
    json_end_array(j);
    json_end_object(j);
}

char *verdict_json_text(const char *job, const struct verdict_study *s, int n, const struct study_env *env)
{
    struct json j;
    json_init(&j);
    json_begin_object(&j, NULL);
    json_string(&j, "job", job);
    json_string(&j, "error",
                "relMSE in linear radiance against each scene's reference: mean over pixels and channels of "
                "(v - r)^2 / (r^2 + 0.01); ranked on its mean log over seeds (value: the geometric mean)");
    json_number(&j, "alpha", VERDICT_ALPHA);
    if (env)
        study_env_json(&j, "reproducibility", env);
    json_string(&j, "tie_rule", TIE_RULE);
    json_begin_array(&j, "studies");
    for (int i = 0; i < n; i++) {
        json_begin_object(&j, NULL);
        json_string(&j, "study", s[i].name);
        if (s[i].machines[0]) { /* its equal-CPU-time rankings mix CPU models (study_machines.h) */
            json_bool(&j, "equal_cpu_time_mixes_machines", 1);
            json_string(&j, "cpu_models", s[i].machines);
        }
        json_begin_array(&j, "scenes");
        for (int k = 0; k < s[i].n_scenes; k++)
            json_scene(&j, &s[i].scenes[k]);
        json_end_array(&j);
        json_end_object(&j);
    }
    json_end_array(&j);
    json_end_object(&j);
    if (j.text.oom) {
        json_free(&j);
        return NULL;
    }
    return j.text.buf; /* the writer's buffer, handed over */
}

/* One cell: "2. 1.3e-3 [1.1e-3, 1.5e-3]", the rank bold when 1. */
static void html_cell(struct sbuf *b, const struct verdict_ranking *r, int v, const char *fmt)
{
    const struct verdict_entry *e = verdict_entry_of(r, v);
    char val[32], lo[32], hi[32];
    if (!e) {
        sbuf_printf(b, "<td></td>");
        return;
    }
    snprintf(val, sizeof val, fmt, e->value);
    snprintf(lo, sizeof lo, fmt, e->lo);
    snprintf(hi, sizeof hi, fmt, e->hi);
    sbuf_printf(b, "<td>%s%d%s &nbsp;%s <span class=\"note\">[%s, %s]%s</span></td>",
                e->rank == 1 && r->status != VERDICT_INCONCLUSIVE ? "<b>" : "", e->rank,
                e->rank == 1 && r->status != VERDICT_INCONCLUSIVE ? "</b>" : "", val, lo, hi,
                e->unreached      ? " not reached: its cheapest point"
                : e->untold       ? " cannot tell: too far beyond its points"
                : e->extrapolated ? " read beyond its cheapest point"
                                  : "");
}

static void html_scene(struct sbuf *b, const struct verdict_scene *v)
{
    html_text(b, "<h3>", v->study, " / ");
    html_text(b, "", v->scene, "</h3>\n<ul class=\"verdict\">\n");
    for (int i = 0; i < v->n_sentences; i++)
        html_text(b, "<li>", v->sentences[i], "</li>\n");
    sbuf_printf(b,
                "</ul>\n<table><tr><th class=\"l\">variant</th><th>rank at equal samples (%.0f spp): relMSE "
                "[95%% CI]</th><th>rank at equal CPU time (%.3g s): relMSE [95%% CI]</th><th>rank by "
                "slope: relMSE ~ spp^s [95%% CI]</th></tr>\n",
                v->by_samples.at, v->by_cpu.at);
    for (int k = 0; k < v->n_variants; k++) {
        html_text(b, "<tr class=\"v\"><td class=\"l\">", v->variants[k], "</td>");
        html_cell(b, &v->by_samples, k, "%.3g");
        html_cell(b, &v->by_cpu, k, "%.3g");
        html_cell(b, &v->by_slope, k, "%.2f");
        sbuf_printf(b, "</tr>\n");
    }
    sbuf_printf(
        b,
        "</table>\n<p class=\"note\">Rankings (relMSE: the %s over seeds, rank_by: %s): at equal samples %s, "
        "at equal CPU time %s, by slope %s.",
        v->rank_by == VERDICT_RANK_MEDIAN ? "median" : "geometric mean",
        v->rank_by == VERDICT_RANK_MEDIAN ? "median" : "mean", status_name(v->by_samples.status),
        status_name(v->by_cpu.status), status_name(v->by_slope.status));
    for (int i = 0; i < v->n_failures; i++)
        html_text(b, i ? "; " : " <b>Failures</b>: ", v->failures[i].text, "");
    sbuf_printf(b, "%s</p>\n", v->n_failures ? "." : " No failure mode detected.");
    for (int i = 0; i < v->n_warnings; i++)
        html_text(b, "<p class=\"warn\">Warning: ", v->warnings[i], "</p>\n");
}

/* One line per study and scene: the three winners and the failures' kinds, at a glance. */
static void html_overview(struct sbuf *b, const struct verdict_study *s, int n)
{
    sbuf_printf(b, "<table><tr><th class=\"l\">study / scene</th><th class=\"l\">best at equal CPU time</th>"
                   "<th class=\"l\">best at equal samples</th><th class=\"l\">fastest slope</th>"
                   "<th class=\"l\">failures found</th></tr>\n");
    for (int i = 0; i < n; i++)
        for (int k = 0; k < s[i].n_scenes; k++) {
            const struct verdict_scene *v = &s[i].scenes[k];
            const struct verdict_ranking *rs[] = {&v->by_cpu, &v->by_samples, &v->by_slope};
            char w[512];
            html_text(b, "<tr class=\"v\"><td class=\"l\">", v->study, " / ");
            html_text(b, "", v->scene, "</td>");
            for (int r = 0; r < 3; r++) {
                verdict_ranking_winner(v, rs[r], 1, w, sizeof w);
                html_text(b, r == 0 ? "<td class=\"l\"><b>" : "<td class=\"l\">", w,
                          r == 0 ? "</b></td>" : "</td>");
            }
            sbuf_printf(b, "<td class=\"l\">");
            for (int f = 0; f < v->n_failures; f++) {
                html_text(b, f ? "; " : "", v->variants[v->failures[f].variant], ": ");
                sbuf_printf(b, "%s", kind_names[v->failures[f].kind][0]);
            }
            sbuf_printf(b, "%s</td></tr>\n", v->n_failures ? "" : "none");
        }
    sbuf_printf(b, "</table>\n");
}

/* The study's error_lowfreq plot, inline, when any was measured. */
static void html_look(struct sbuf *b, const struct verdict_study *s)
{
    int any = 0;
    for (int k = 0; k < s->n_scenes; k++)
        for (int i = 0; i < s->scenes[k].n_variants * s->scenes[k].n_points; i++)
            any |= isfinite(s->scenes[k].look.mean[i]);
    char *svgs[2] = {any ? report_look_svg(s, REPORT_LOOK_LOWFREQ) : NULL,
                     report_look_svg(s, REPORT_LOOK_SPECTRUM)};
    for (int i = 0; i < 2; i++) {
        const char *root = svgs[i] ? strstr(svgs[i], "<svg") : NULL; /* inline: drop the XML declaration */
        if (root)
            sbuf_printf(b, "<div class=\"look\">%s</div>\n", root);
        free(svgs[i]);
    }
}

void verdict_html(struct sbuf *b, const struct verdict_study *s, int n)
{
    sbuf_printf(b, "<section id=\"verdict\"><h2>Verdict</h2>\n");
    html_overview(b, s, n);
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < s[i].n_scenes; k++)
            html_scene(b, &s[i].scenes[k]);
        html_look(b, &s[i]);
    }
    html_text(b, "<p class=\"note\"><b>How it is decided.</b> Errors are relMSE in linear radiance. ",
              TIE_RULE, "");
    sbuf_printf(
        b,
        " Failure modes: more than %.0f%% of the error repeating in every seed (structured: averaging "
        "the seeds' images leaves it); a step along the sweep whose local slope is above %.1f (error "
        "stops falling); any non-finite sample; a sampler taking more than %.0f%% of the CPU time. "
        "The same verdict is in <a href=\"verdict.json\">verdict.json</a>.</p></section>\n",
        100 * VERDICT_STRUCTURED_SHARE, VERDICT_STALL_SLOPE, 100 * VERDICT_SAMPLER_SHARE);
}

void verdict_summary(const struct verdict_study *s, int n, char *buf, size_t len)
{
    size_t at = 0;
    buf[0] = 0;
    for (int i = 0; i < n && at < len; i++) {
        at += (size_t)snprintf(buf + at, len - at, "%s%s:", i ? "; " : "", s[i].name);
        for (int k = 0; k < s[i].n_scenes && at < len; k++) {
            char w[256];
            verdict_ranking_winner(&s[i].scenes[k], &s[i].scenes[k].by_cpu, 1, w, sizeof w);
            at += (size_t)snprintf(buf + at, len - at, "%s %s %s", k ? "," : "", s[i].scenes[k].scene, w);
        }
    }
}

void verdict_print_warnings(const struct verdict_study *s, int n)
{
    for (int i = 0; i < n; i++)
        for (int k = 0; k < s[i].n_scenes; k++)
            for (int w = 0; w < s[i].scenes[k].n_warnings; w++)
                err_print("%s: warning: %s: %s\n", s[i].name, s[i].scenes[k].scene,
                          s[i].scenes[k].warnings[w]);
}
