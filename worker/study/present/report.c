/* report: the compare job's HTML page: chart, images side by side, crops, error maps, table. */
#include "report.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study/judge/compare_stats.h"
#include "report_chart.h"
#include "report_stability.h"
#include "report_closeup.h"
#include "image/errmap.h"
#include "report_image.h"
#include "report_view.h"
#include "base/sbuf.h"
#include "study/load/html_text.h"
#include "verdict_out.h"

static const char report_style[] =
    "body{font-family:sans-serif;margin:16px;color:#222}p,ul,h3{max-width:1180px}"
    "h1{font-size:22px}h2{font-size:19px;border-top:2px solid #ddd;padding-top:10px}h3{font-size:15px}"
    ".row{display:flex;flex-wrap:wrap;gap:8px;align-items:flex-start;margin-bottom:8px}"
    "figure{margin:0;font-size:12px;width:min-content}figcaption{min-width:120px}"
    "img{display:block;border:1px solid #ccc}"
    "svg{max-width:100%;height:auto}" /* a long label's legend makes the chart wider than the page */
    "table{border-collapse:collapse;font-size:12px}td,th{border:1px solid #ccc;padding:2px "
    "6px;text-align:right}"
    "td.l,th.l{text-align:left}.pt{font-weight:bold;font-size:13px;flex-basis:100%}"
    ".note{color:#555;font-size:13px}li{margin-bottom:4px}"
    ".warn{color:#8a4b00;background:#fff4e0;padding:4px "
    "8px;font-size:13px}ul.verdict{font-size:15px}" REPORT_VIEW_CSS;

/* What every figure of scene s's image grid shares: renders read from dir, shown at zoom; ab: the
   id of the reference the A/B toggle shows in a render's place, or NULL. */
struct grid {
    const struct compare *c;
    int s;
    const char *dir;
    int zoom;
    const char *ab;
};

/* One render of the grid (variant v, sweep point p, seed index k) as a figure with its caption. */
static int grid_figure(struct sbuf *b, const struct grid *g, int v, int p, int k, struct err *e)
{
    const struct compare *c = g->c;
    int s = g->s;
    const struct compare_item *it = &c->items[compare_index(c, s, v, p, k)];
    const struct study_result *r = &c->results.rows[compare_index(c, s, v, p, k)];
    char path[4096], alt[256], slot[32];
    uint8_t *png;
    size_t len;
    snprintf(path, sizeof path, "%s/%s", g->dir, it->job.output);
    if (report_view_read_png(path, &png, &len, NULL, e) < 0)
        return -1;
    snprintf(alt, sizeof alt, "%s %s", c->variants[v], it->job.output);
    snprintf(slot, sizeof slot, "g%dv%d", p, v);
    struct report_view_img view = {g->zoom, NULL, g->ab, alt};
    report_view_figure(b, k, slot);
    report_view_png(b, png, len, c->scenes[s].width, c->scenes[s].height, &view);
    free(png);
    html_text(b, "<figcaption><b>", c->variants[v], "");
    sbuf_printf(b, "</b> t=%g: %.0f spp", it->job.spec.pixel.threshold, r->spp_mean);
    if (r->has_error)
        sbuf_printf(b, ", relMSE %.3g", r->error.relmse);
    sbuf_printf(b, ", %.2f s, seed %llu</figcaption></figure>\n", r->wall_s, (unsigned long long)c->seeds[k]);
    return 0;
}

/* Rows of images: one row per sweep point, the variants side by side, every seed (seed index 0
   shown; the scene's bar switches). */
static int image_grid(struct sbuf *b, const struct compare *c, int s, const char *dir, int zoom, int has_ref,
                      struct err *e)
{
    char ab[32];
    snprintf(ab, sizeof ab, "ref%d", s);
    const struct grid g = {c, s, dir, zoom, has_ref ? ab : NULL};
    for (int p = 0; p < c->n_points; p++) {
        html_text(b, "<div class=\"row\"><div class=\"pt\">", c->points[p], ", ");
        for (int k = 0; k < c->n_seeds; k++)
            sbuf_printf(b, "<span class=\"sd\" data-seed=\"%d\"%s>seed %llu</span>", k, k ? " hidden" : "",
                        (unsigned long long)c->seeds[k]);
        sbuf_printf(b, "</div>\n");
        for (int v = 0; v < c->n_variants; v++)
            for (int k = 0; k < c->n_seeds; k++)
                if (grid_figure(b, &g, v, p, k, e) < 0)
                    return -1;
        sbuf_printf(b, "</div>\n");
    }
    return 0;
}

/* The scene's reference (its pixels as the study scored against them, rr->ref), at the renders'
   zoom, with id ref<s> (what the A/B toggle shows). */
static int reference_figure(struct sbuf *b, const struct compare_scene *cs, const struct study_ref_result *rr,
                            int s, int zoom, struct err *e)
{
    char id[32];
    snprintf(id, sizeof id, "ref%d", s);
    struct report_view_img view = {zoom, id, NULL, "reference"};
    const struct rgb8 *ref = &rr->ref->display; /* an EXR's floats converted as the PNG writer does */
    struct rgb8 out = {0};                      /* with the mask's outline */
    sbuf_printf(b, "<div class=\"row\"><figure>");
    int rc = cs->mask && image_alloc(&out, ref->w, ref->h, e) < 0;
    if (rc == 0 && cs->mask) {
        memcpy(out.px, ref->px, (size_t)ref->w * ref->h * 3);
        errmap_outline(&out, cs->mask);
    }
    rc = rc || report_view_rgb(b, cs->mask ? &out : ref, &view, e) < 0;
    image_free(&out);
    if (rc)
        return -1;
    sbuf_printf(b, "<figcaption><b>reference</b>: ");
    char light[96];
    if (cs->ref_kind == COMPARE_REF_SETTINGS)
        sbuf_printf(b, "%s t=%g, %s, seed %llu; %s %.1f s", sampler_kind_name(cs->ref_job.spec.pixel.kind),
                    cs->ref_job.spec.pixel.threshold, job_light_text(&cs->ref_job, light, sizeof light),
                    (unsigned long long)cs->ref_job.spec.seed,
                    rr->fig.reused ? "reused from cache, rendered in" : "rendered in", rr->fig.wall_s);
    else
        sbuf_escape(b, rr->path);
    if (cs->mask)
        sbuf_printf(b, "; every figure counts only the %zu pixels inside the cyan outline (mask)",
                    cs->mask->count);
    sbuf_printf(b, "</figcaption></figure></div>\n");
    return 0;
}

static int scene_section(struct sbuf *b, const struct compare *c, int s, const char *dir, struct err *e)
{
    const struct compare_scene *cs = &c->scenes[s];
    const struct study_ref_result *rr = &c->results.refs[s];
    int has_ref = cs->ref_kind != COMPARE_REF_NONE, linear = cs->ref_domain == IMG_LINEAR;
    if (has_ref && !rr->ref)
        return err_set(e, NULL, 0, 0, "%s: the reference of %s was not prepared", c->name, cs->name);
    int zoom = report_image_zoom(cs->width, REPORT_IMAGE_SHOW_PX);
    html_text(b, "<section class=\"scene\"><h2>Scene ", cs->name, "");
    sbuf_printf(b, " (%dx%d)</h2>\n", cs->width, cs->height);
    report_view_controls(b, c, zoom, has_ref);
    if (has_ref && reference_figure(b, cs, rr, s, zoom, e) < 0)
        return -1;
    sbuf_printf(b, "<h3>Side by side at each sweep point, with samples per pixel</h3>\n");
    if (image_grid(b, c, s, dir, zoom, has_ref, e) < 0)
        return -1;
    if (has_ref) {
        int *order = calloc((size_t)c->n_points, sizeof *order);
        if (!order)
            return err_set(e, NULL, 0, 0, "out of memory");
        compare_stats_point_order(c, s, 0, order);
        int mid = order[c->n_points / 2], densest = order[c->n_points - 1];
        free(order);
        const struct rgbf *reff = linear ? &rr->ref->f : NULL;
        if (report_closeup(b, c, s, mid, dir, &rr->ref->display, reff, e) < 0 ||
            (densest != mid && report_closeup(b, c, s, densest, dir, &rr->ref->display, reff, e) < 0))
            return -1;
    }
    sbuf_printf(b, "<h3>Stability</h3>\n<ul>\n");
    for (int v = 0; v < c->n_variants; v++) {
        char *line = report_stability(c, s, v);
        html_text(b, "<li><b>", c->variants[v], "</b>: ");
        html_text(b, "", line ? line : "out of memory", "</li>\n");
        free(line);
    }
    sbuf_printf(b, "</ul>\n</section>\n");
    return 0;
}

void report_link(struct sbuf *b, const char *href, const char *text)
{
    sbuf_printf(b, "<a href=\"");
    for (const unsigned char *p = (const unsigned char *)href; *p; p++)
        if (isalnum(*p) || strchr("-._~/", *p))
            sbuf_printf(b, "%c", *p);
        else
            sbuf_printf(b, "%%%02X", *p);
    html_text(b, "\">", text, "</a>");
}

void report_head(struct sbuf *b, const char *name, int n_studies)
{
    html_text(b, "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>", name,
              ": samplers compared");
    if (n_studies > 0)
        sbuf_printf(b, " in %d studies", n_studies);
    sbuf_printf(b, "</title><style>%s</style></head><body>\n<h1>", report_style);
    html_text(b, "", name, ": which sampler gives the better picture for the time spent</h1>\n");
}

void report_study_shape(struct sbuf *b, const struct compare *c)
{
    sbuf_printf(b, "%d image%s = %d scene%s x %d variant%s x %d sweep point%s", c->n_items,
                sbuf_plural(c->n_items), c->n_scenes, sbuf_plural(c->n_scenes), c->n_variants,
                sbuf_plural(c->n_variants), c->n_points, sbuf_plural(c->n_points));
    if (c->sweep_keys[0])
        html_text(b, " (sweep: ", c->sweep_keys, ")");
    sbuf_printf(b, " x %d seed%s", c->n_seeds, sbuf_plural(c->n_seeds));
}

static void table(struct sbuf *b, const struct compare *c)
{
    /* the work counts beside the times: the same on every machine (summary.csv has them all) */
    const char *head[] = {
        "scene",         "variant",  NULL,          NULL,         NULL,  "spp mean", "wall s", "cpu s",
        "sampler share", "segments", "shadow rays", "set points", "mse", "rmse",     "relmse", "psnr dB",
        "image, sidecar"};
    /* the settings' heads: their labels in render_spec's rows */
    const char *const settings[] = {"threshold", "light_threshold", "seed"};
    for (int k = 0; k < 3; k++)
        head[2 + k] = render_spec_find(settings[k])->label;
    const size_t n_head = sizeof head / sizeof head[0];
    sbuf_printf(b, "<table>\n<tr>");
    for (size_t i = 0; i < n_head; i++)
        sbuf_printf(b, "<th%s>%s</th>", i < 2 || i == n_head - 1 ? " class=\"l\"" : "", head[i]);
    sbuf_printf(b, "</tr>\n");
    for (int i = 0; i < c->n_items; i++) {
        const struct compare_item *it = &c->items[i];
        const struct study_result *r = &c->results.rows[i];
        html_text(b, "<tr><td class=\"l\">", c->scenes[it->scene].name, "</td><td class=\"l\">");
        html_text(b, "", c->variants[it->variant], "");
        sbuf_printf(
            b, "</td><td>%g</td><td>%g</td><td>%llu</td><td>%.0f</td><td>%.3f</td><td>%.3f</td><td>%.3f</td>",
            it->job.spec.pixel.threshold, it->job.spec.light.threshold, (unsigned long long)it->job.spec.seed,
            r->spp_mean, r->wall_s, r->cpu_s, r->sampler_share);
        const struct sidecar_work *w = &r->work;
        sbuf_printf(b, "<td>%llu</td><td>%llu</td><td>%llu</td>", (unsigned long long)w->path_segments,
                    (unsigned long long)w->shadow_rays,
                    (unsigned long long)(w->pixel_points + w->light_points + w->padded_points));
        if (r->has_error)
            sbuf_printf(b, "<td>%.4g</td><td>%.4g</td><td>%.4g</td><td>%.2f</td>", r->error.mse,
                        r->error.rmse, r->error.relmse, r->error.psnr);
        else
            sbuf_printf(b, "<td></td><td></td><td></td><td></td>");
        char sidecar[JOB_PATH_MAX + 8];
        snprintf(sidecar, sizeof sidecar, "%.*s.json", (int)strlen(it->job.output) - 4, it->job.output);
        sbuf_printf(b, "<td class=\"l\">");
        report_link(b, it->job.output, it->job.output);
        sbuf_printf(b, ", ");
        report_link(b, sidecar, "json");
        sbuf_printf(b, "</td></tr>\n");
    }
    sbuf_printf(b, "</table>\n");
}

char *report_html(const struct compare *c, const char *dir, struct err *e)
{
    struct sbuf b = {0};
    char *svg = report_chart_svg(c);
    if (!svg) {
        err_set(e, NULL, 0, 0, "out of memory drawing the chart");
        return NULL;
    }
    report_head(&b, c->name, 0);
    if (c->has_verdict)
        verdict_html(&b, &c->verdict, 1);
    html_text(&b, "<h2>What was measured</h2>\n<p class=\"note\">Job ", c->path, ": ");
    report_study_shape(&b, c);
    sbuf_printf(
        &b, ". Errors are in linear radiance: relMSE is the mean of (image - reference)^2 / "
            "(reference^2 + 0.01) over the renders' unclipped float values (each PNG's float image is the "
            ".exr beside it) against each scene's reference; lower is better. Measured on the 8-bit PNGs "
            "instead, the clip at white would hide the lights, their reflections and fireflies, and the "
            "gamma curve and 1/255 steps would weight dark pixels more and set a floor (summary.csv keeps "
            "those figures as relmse_8bit). The reference's own noise sets a floor under every curve (the "
            "verdict measures it from the "
            "reference's two halves and takes it out: reference_relmse). Wall "
            "time is one image's render on this machine, so it moves with the machine's load. Every image "
            "and its JSON sidecar are beside this page (linked from the table at the end), with <a "
            "href=\"summary.csv\">summary.csv</a> (the table's figures) and <a "
            "href=\"chart.svg\">chart.svg</a>.</p>\n");
    for (int s = 0; s < c->n_scenes; s++)
        if (c->scenes[s].ref_kind != COMPARE_REF_NONE && c->scenes[s].ref_domain == IMG_DISPLAY8) {
            html_text(&b, "<p class=\"note\"><b>Scene ", c->scenes[s].name,
                      "'s reference is an 8-bit PNG/PPM: its errors are measured on 8-bit display "
                      "values, not in linear radiance.</b></p>\n");
        }
    const char *body = strstr(svg, "<svg"); /* inline: drop the XML declaration */
    sbuf_printf(&b, "<h2>Speed against accuracy</h2>\n%s\n", body ? body : svg);
    free(svg);
    for (int s = 0; s < c->n_scenes; s++)
        if (scene_section(&b, c, s, dir, e) < 0) {
            sbuf_free(&b);
            return NULL;
        }
    sbuf_printf(&b, "<h2>Every image</h2>\n");
    table(&b, c);
    study_env_html(&b, &c->env);
    sbuf_printf(&b, "<script>%s</script>\n</body></html>\n", report_view_script);
    char *html = sbuf_take(&b);
    if (!html)
        err_set(e, NULL, 0, 0, "out of memory writing the report");
    return html;
}
