/* test_chart: the SVG writer: decade axes, skipped non-positive points, escaping, empty panels. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study/present/chart.h"
#include "check.h"

static int count(const char *s, const char *what)
{
    int n = 0;
    for (const char *p = s; (p = strstr(p, what)); p++)
        n++;
    return n;
}

int main(void)
{
    /* x from 2 to 50 and y from 0.003 to 0.2: axes widen to whole decades 1..100 and 0.001..1 */
    double x[] = {2, 5, 50, -1}, y[] = {0.2, 0.05, 0.003, 0.1};
    double lo[] = {0.15, 0.04, 0.002, 0.1}, hi[] = {0.25, 0.06, 0.004, 0.1};
    double y2[] = {0.1, 0.02, 0, 0.01};
    struct chart_series ser[2] = {{"a<b&c", 4, x, y, lo, hi}, {"second", 4, x, y2, NULL, NULL}};
    static const double slopes[] = {-1, -1.5};
    struct chart_panel p[2] = {
        {"first & panel", "time (s)", "relMSE", NULL, ser, 2, slopes, 2, "whisker: 95% CI"},
        {"empty", "x", "y", "nothing to show", ser, 0, NULL, 0, NULL}};
    char *svg = chart_svg("title <1>", p, 2, 2);
    CHECK(svg != NULL);
    if (!svg)
        return check_report("test_chart");
    CHECK(strncmp(svg,
                  "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\"",
                  77) == 0);
    CHECK(strstr(svg, "</svg>\n") != NULL);
    CHECK(strstr(svg, "title &lt;1&gt;") != NULL);
    CHECK(strstr(svg, "first &amp; panel") != NULL);
    CHECK(strstr(svg, ">a&lt;b&amp;c<") != NULL); /* the legend escapes names */
    CHECK(!strstr(svg, "a<b"));
    CHECK(count(svg, "<polyline") == 2);
    /* series 1: x = -1 skipped; series 2: y = 0 skipped too: 3 + 2 points */
    CHECK(count(svg, "<circle") == 5);
    CHECK(count(svg, "<path d=\"M") == 3 + 1);      /* three whiskers + the legend's sample whisker */
    CHECK(count(svg, "stroke-dasharray") == 2 + 1); /* two guides + the legend's sample */
    CHECK(strstr(svg, ">slope -1.5<") != NULL);
    CHECK(strstr(svg, ">time (s)<") != NULL);
    /* decade tick labels of both axes */
    CHECK(strstr(svg, ">100<") && strstr(svg, ">1<") && strstr(svg, ">1e-3<") && strstr(svg, ">0.01<"));
    CHECK(strstr(svg, ">nothing to show<") != NULL);
    CHECK(strstr(svg, "whisker: 95% CI") != NULL); /* the panel's own words for its whiskers */
    /* 10 sits in the middle of 1..100: plot x = 74 + 390 / 2 = 269 (panel 480 wide, margins 74 and 16) */
    double xs[] = {1.5, 10, 90}, ys[] = {0.5, 0.05, 0.005};
    struct chart_series one = {"one", 3, xs, ys, NULL, NULL};
    struct chart_panel q = {"t", "x", "y", NULL, &one, 1, NULL, 0, NULL};
    char *svg2 = chart_svg("t", &q, 1, 1);
    CHECK(svg2 && strstr(svg2, "points=\"") && strstr(strstr(svg2, "points=\""), " 269.0,"));
    CHECK(svg2 && !strstr(svg2, "whisker")); /* no whiskers drawn: none in the legend */
    CHECK(strstr(chart_color(0), "#") && strcmp(chart_color(1), chart_color(9)) == 0);
    /* a variant keeps its colour whatever the other series of its chart (two studies on a page) */
    {
        struct chart_series a[2] = {{"jitter", 3, xs, ys, NULL, NULL}, {"sobol", 3, xs, ys, NULL, NULL}};
        struct chart_series b[2] = {{"sobol", 3, xs, ys, NULL, NULL}, {"random", 3, xs, ys, NULL, NULL}};
        struct chart_panel pa = {"a", "x", "y", NULL, a, 2, NULL, 0, NULL},
                           pb = {"b", "x", "y", NULL, b, 2, NULL, 0, NULL};
        char *sa = chart_svg("a", &pa, 1, 1), *sb = chart_svg("b", &pb, 1, 1);
        const char *ca = sa ? strstr(sa, "stroke=\"#") : NULL, *cb = sb ? strstr(sb, "stroke=\"#") : NULL;
        /* the first polyline of a is jitter's, of b sobol's: find sobol's in a (the second) */
        if (ca)
            ca = strstr(strstr(ca, "<polyline") + 1, "<polyline");
        if (ca)
            ca = strstr(ca, "stroke=\"#");
        if (cb)
            cb = strstr(strstr(sb, "<polyline"), "stroke=\"#");
        CHECK(ca && cb && strncmp(ca, cb, 15) == 0);
        free(sa);
        free(sb);
    }
    /* a long label (up to 63 characters) fits inside the legend box and the drawing */
    struct chart_series longer = {
        "poisson-lightjitter-pool64-depth8-a-label-as-long-as-allowed-xy", 3, xs, ys, NULL, NULL};
    struct chart_panel r = {"t", "x", "y", NULL, &longer, 1, NULL, 0, NULL};
    char *svg3 = chart_svg("t", &r, 1, 1);
    int svg_w = 0;
    double box_x = 0, box_w = 0;
    const char *box = svg3 ? strstr(svg3, "stroke=\"#cccccc\"") : NULL; /* the legend's frame */
    while (box && box > svg3 && strncmp(box, "<rect", 5))
        box--;
    CHECK(svg3 && sscanf(svg3 + 39, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\"", &svg_w) == 1);
    CHECK(box && sscanf(box, "<rect x=\"%lf\" y=\"%*f\" width=\"%lf\"", &box_x, &box_w) == 2);
    /* sans-serif at 12 px is under 7 px a character; the text starts 34 px into the box */
    CHECK(box_w >= 34 + 7 * 63 && box_x + box_w <= svg_w);
    /* guide labels that would end close together (a narrow y range) do not overlap: each is
       right-aligned at its end, "slope -1.5" at 11 px about 60 px wide and 12 px high */
    double xn[] = {1, 1.2}, yn[] = {0.015, 0.012};
    struct chart_series near = {"near", 2, xn, yn, NULL, NULL};
    struct chart_panel u = {"t", "x", "y", NULL, &near, 1, slopes, 2, NULL};
    char *svg4 = chart_svg("t", &u, 1, 1);
    double lx[2] = {0, 0}, ly[2] = {0, 0};
    int labels = 0;
    for (const char *t = svg4; t && (t = strstr(t, "<text x=\"")) && labels < 2; t++) {
        const char *close = strchr(t, '>');
        if (close && !strncmp(close, ">slope ", 7) &&
            sscanf(t, "<text x=\"%lf\" y=\"%lf\"", &lx[labels], &ly[labels]) == 2)
            labels++;
    }
    CHECK(labels == 2);
    CHECK(fabs(lx[0] - lx[1]) >= 60 || fabs(ly[0] - ly[1]) >= 12);
    /* that panel spans a decade in y (0.01..0.1): with only its two ends labelled no value can
       be read, so 2 and 5 times each decade are labelled too */
    CHECK(svg4 && strstr(svg4, ">0.02<") && strstr(svg4, ">0.05<"));
    CHECK(svg4 && strstr(svg4, ">2<") && strstr(svg4, ">0.5<"));   /* x: 0.1..10, two decades */
    CHECK(svg && !strstr(svg, ">0.02<") && !strstr(svg, ">0.5<")); /* y: three decades, decades only */
    free(svg4);
    /* the guides start at the highest point, where error is largest, even when the leftmost point
       is low (noisy wall times): from there they run across the data, not below it */
    double xg[] = {1, 2, 5}, yg[] = {0.001, 0.1, 0.01}, gx = 0, gy = 0, cx = 0, cy = 0;
    struct chart_series hi_pt = {"g", 3, xg, yg, NULL, NULL};
    struct chart_panel gp = {"t", "x", "y", NULL, &hi_pt, 1, slopes, 2, NULL};
    char *svg5 = chart_svg("t", &gp, 1, 1);
    const char *guide = svg5 ? strstr(svg5, "stroke-dasharray=\"2 4\"") : NULL;
    while (guide && guide > svg5 && strncmp(guide, "<line", 5))
        guide--;
    const char *circle = svg5 ? strstr(svg5, "<circle") : NULL;
    circle = circle ? strstr(circle + 1, "<circle") : NULL; /* the second point's */
    CHECK(guide && sscanf(guide, "<line x1=\"%lf\" y1=\"%lf\"", &gx, &gy) == 2);
    CHECK(circle && sscanf(circle, "<circle cx=\"%lf\" cy=\"%lf\"", &cx, &cy) == 2);
    CHECK(gx == cx && gy == cy);
    free(svg5);
    free(svg3);
    free(svg2);
    free(svg);
    return check_report("test_chart");
}
