/* compare_suite_out: a suite's summary.csv, chart.svg and report.html, from its studies' own. */
#include "compare_suite_out.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fileio.h"
#include "base/sbuf.h"
#include "report_chart.h"
#include "report.h"
#include "study/load/html_text.h"
#include "study/load/verdict_csv.h"

/* Largest study summary.csv read back: 4096 rows of a few hundred bytes each, with room. */
#define SUITE_CSV_MAX_BYTES (64u << 20)

/* One CSV record: first (unquoted, a study name: letters, digits, '-', '_', '.'), then the fields,
   each quoted as the study's summary.csv had it (sbuf_csv: the bytes written again as they were). */
static void record(struct sbuf *b, const char *first, char *const *f, int n)
{
    sbuf_printf(b, "%s", first);
    for (int k = 0; k < n; k++) {
        sbuf_printf(b, ",");
        sbuf_csv(b, f[k]);
    }
    sbuf_printf(b, "\n");
}

char *compare_suite_csv(const struct compare_suite *s, const char *dir, struct err *e)
{
    struct sbuf b = {0};
    for (int i = 0; i < s->n_studies; i++) {
        const struct compare *c = s->studies[i];
        char path[4096];
        uint8_t *data;
        size_t len;
        struct verdict_csv t;
        snprintf(path, sizeof path, "%s/%s/summary.csv", dir, c->name);
        int rc = fileio_read_all(path, SUITE_CSV_MAX_BYTES, &data, &len, e);
        if (rc == 0 && (rc = verdict_csv_parse(&t, (char *)data, len, path, e)) < 0)
            free(data);
        if (rc < 0) {
            sbuf_free(&b);
            return NULL;
        }
        for (int r = i == 0 ? 0 : 1; r < t.n_rows; r++) /* every study's header is the same */
            record(&b, r == 0 ? "study" : c->name, t.rows[r], t.n_fields);
        verdict_csv_free(&t);
        free(data);
    }
    char *text = sbuf_take(&b);
    if (!text)
        err_set(e, NULL, 0, 0, "out of memory writing the suite's summary.csv");
    return text;
}

char *compare_suite_chart_svg(const struct compare_suite *s)
{
    struct sbuf body = {0}, b = {0};
    int w = 0, h = 0;
    for (int i = 0; i < s->n_studies; i++) {
        char *svg = report_chart_svg(s->studies[i]);
        const char *root = svg ? strstr(svg, "<svg ") : NULL;
        int sw, sh;
        if (!root || sscanf(root, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\"", &sw,
                            &sh) != 2) {
            free(svg);
            sbuf_free(&body);
            return NULL;
        }
        /* each study's chart as a nested <svg>, placed below the one before */
        sbuf_printf(&body, "<svg x=\"0\" y=\"%d\"%s", h, root + 4);
        h += sh;
        w = sw > w ? sw : w;
        free(svg);
    }
    sbuf_printf(
        &b,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
        "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"%d\" height=\"%d\" fill=\"#ffffff\"/>\n",
        w, h, w, h, w, h);
    if (body.buf)
        sbuf_printf(&b, "%s", body.buf);
    sbuf_printf(&b, "</svg>\n");
    if (body.oom)
        sbuf_free(&b);
    sbuf_free(&body);
    return sbuf_take(&b);
}

/* One study's section: its name, its shape, a link to its report, its chart. */
static int study_section(struct sbuf *b, const struct compare *c, struct err *e)
{
    char href[JOB_NAME_MAX + 16];
    char *svg = report_chart_svg(c);
    if (!svg)
        return err_set(e, NULL, 0, 0, "out of memory drawing %s's chart", c->name);
    html_text(b, "<h2 id=\"study-", c->name, "\">");
    html_text(b, "", c->name, "</h2>\n<p class=\"note\">Study ");
    html_text(b, "", c->path, ": ");
    report_study_shape(b, c);
    snprintf(href, sizeof href, "%s/report.html", c->name);
    sbuf_printf(b, ". Its own page, with every image, crops, error maps and the table: ");
    report_link(b, href, href);
    sbuf_printf(b, ".</p>\n");
    const char *root = strstr(svg, "<svg"); /* inline: drop the XML declaration */
    sbuf_printf(b, "%s\n", root ? root : svg);
    free(svg);
    return 0;
}

char *compare_suite_report_html(const struct compare_suite *s, const struct verdict_study *v, struct err *e)
{
    struct sbuf b = {0};
    report_head(&b, s->name, s->n_studies);
    html_text(&b, "<p class=\"note\">Suite ", s->path, "");
    sbuf_printf(&b, ": %d images in %d studies, each an ordinary compare job with its own folder and page:",
                s->n_items, s->n_studies);
    for (int i = 0; i < s->n_studies; i++) {
        char href[JOB_NAME_MAX + 16];
        snprintf(href, sizeof href, "%s/report.html", s->studies[i]->name);
        sbuf_printf(&b, "%s", i ? ", " : " ");
        report_link(&b, href, s->studies[i]->name);
    }
    sbuf_printf(&b,
                ". Every study's figures are in <a href=\"summary.csv\">summary.csv</a> (its first column "
                "names the study), their verdict in <a href=\"verdict.json\">verdict.json</a> and their "
                "charts in <a href=\"chart.svg\">chart.svg</a>.</p>\n");
    verdict_html(&b, v, s->n_studies);
    for (int i = 0; i < s->n_studies; i++)
        if (study_section(&b, s->studies[i], e) < 0) {
            sbuf_free(&b);
            return NULL;
        }
    if (s->n_studies > 0)
        study_env_html(&b, &s->studies[0]->env);
    sbuf_printf(&b, "</body></html>\n");
    char *html = sbuf_take(&b);
    if (!html)
        err_set(e, NULL, 0, 0, "out of memory writing the suite's report");
    return html;
}
