/* chart: log-log panels as SVG: decade grid, labelled axes, whiskers, legend, dotted guides. */
#include "chart.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/hash.h"
#include "base/sbuf.h"
#include "study/load/html_text.h"

#define PANEL_W 480
#define PANEL_H 340
#define MARGIN_L 74 /* room for tick labels and the y label */
#define MARGIN_R 16
#define MARGIN_T 34
#define MARGIN_B 50
#define TITLE_H 34
#define LEGEND_W 170     /* the narrowest legend column, right of each row of panels */
#define LEGEND_TEXT_X 34 /* where a legend entry's text starts in its box */
#define CHAR_W 7         /* a generous width of one character at 12 px sans-serif */

#define PALETTE 8

const char *chart_color(int i)
{
    static const char *const palette[PALETTE] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                                 "#9467bd", "#8c564b", "#e377c2", "#17becf"};
    return palette[(i < 0 ? -i : i) % PALETTE];
}

/* Series s's colour in panel p: the palette slot its name hashes to, so a variant keeps its colour
   across the studies on one page; on a clash within the panel the next free slot (by series
   order, so every panel of one study agrees). */
static const char *series_color(const struct chart_panel *p, int s)
{
    int used[PALETTE] = {0}, slot = 0;
    for (int i = 0; i <= s; i++) {
        const char *name = p->series[i].name ? p->series[i].name : "";
        slot = (int)(hash_bytes(HASH_FNV_OFFSET, name, strlen(name)) % PALETTE);
        for (int k = 0; k < PALETTE && used[slot]; k++)
            slot = (slot + 1) % PALETTE;
        used[slot] = 1;
    }
    return chart_color(slot);
}

/* The data range of a panel in log10 units; 0 when nothing is drawable. */
struct range {
    double x0, x1, y0, y1;
};

static int usable(double v)
{
    return isfinite(v) && v > 0;
}

static int data_range(const struct chart_panel *p, struct range *r)
{
    int any = 0;
    *r = (struct range){INFINITY, -INFINITY, INFINITY, -INFINITY};
    for (int s = 0; s < p->n_series; s++) {
        const struct chart_series *se = &p->series[s];
        for (int i = 0; i < se->n; i++) {
            if (!usable(se->x[i]) || !usable(se->y[i]))
                continue;
            double ys[3] = {se->y[i], se->lo ? se->lo[i] : se->y[i], se->hi ? se->hi[i] : se->y[i]};
            r->x0 = fmin(r->x0, log10(se->x[i]));
            r->x1 = fmax(r->x1, log10(se->x[i]));
            for (int k = 0; k < 3; k++)
                if (usable(ys[k])) {
                    r->y0 = fmin(r->y0, log10(ys[k]));
                    r->y1 = fmax(r->y1, log10(ys[k]));
                }
            any = 1;
        }
    }
    if (!any)
        return 0;
    /* Widen to whole decades (at least one), so the axes read as powers of ten. */
    r->x0 = floor(r->x0 - 0.02), r->x1 = ceil(r->x1 + 0.02);
    r->y0 = floor(r->y0 - 0.02), r->y1 = ceil(r->y1 + 0.02);
    return 1;
}

/* Panel-local mapping from log10 data to pixels. */
struct frame {
    double left, top, w, h;
    struct range r;
};

static double px(const struct frame *f, double v)
{
    return f->left + (log10(v) - f->r.x0) / (f->r.x1 - f->r.x0) * f->w;
}

static double py(const struct frame *f, double v)
{
    return f->top + (f->r.y1 - log10(v)) / (f->r.y1 - f->r.y0) * f->h;
}

/* The tick label of m x 10^e ("1e-5", "0.02", "100", "5e4") at `at` along the x axis (below it) or
   the y axis (left of it). */
static void tick(struct sbuf *b, const struct frame *f, int y_axis, double at, int m, int e, const char *fill)
{
    char lab[32];
    if (e >= -2 && e <= 3)
        snprintf(lab, sizeof lab, "%g", m * pow(10, e));
    else
        snprintf(lab, sizeof lab, "%de%d", m, e);
    sbuf_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\"%s>%s</text>\n", y_axis ? f->left - 6 : at,
                y_axis ? at + 4 : f->top + f->h + 16, y_axis ? "end" : "middle", fill, lab);
}

/* An axis spanning at most this many decades also labels 2 and 5 times each decade: with only
   its ends labelled, a value in between could not be read. */
#define MINOR_LABEL_DECADES 2

/* One axis's grid (across the frame) and tick labels: x along the bottom, or y up the left. */
static void axis(struct sbuf *b, const struct frame *f, int y_axis)
{
    double lo = y_axis ? f->r.y0 : f->r.x0, hi = y_axis ? f->r.y1 : f->r.x1;
    int decades = (int)(hi - lo);
    for (int e = (int)lo; e <= (int)hi; e++) {
        for (int m = 1; m <= 9 && e < (int)hi; m++) { /* minor grid at 2..9 x 10^e */
            double at = y_axis ? py(f, m * pow(10, e)) : px(f, m * pow(10, e));
            sbuf_printf(b, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\"/>\n",
                        y_axis ? f->left : at, y_axis ? at : f->top, y_axis ? f->left + f->w : at,
                        y_axis ? at : f->top + f->h, m == 1 ? "#bbbbbb" : "#eeeeee");
            if ((m == 2 || m == 5) && decades <= MINOR_LABEL_DECADES)
                tick(b, f, y_axis, at, m, e, " fill=\"#666666\"");
        }
        if (decades <= 8 || e % 2 == 0)
            tick(b, f, y_axis, y_axis ? py(f, pow(10, e)) : px(f, pow(10, e)), 1, e, "");
    }
}

static void axes(struct sbuf *b, const struct frame *f, const struct chart_panel *p)
{
    sbuf_printf(
        b,
        "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#ffffff\" stroke=\"#444444\"/>\n",
        f->left, f->top, f->w, f->h);
    axis(b, f, 0);
    axis(b, f, 1);
    sbuf_printf(b, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">", f->left + f->w / 2,
                f->top + f->h + 36);
    sbuf_escape(b, p->x_label);
    sbuf_printf(b, "</text>\n<text transform=\"translate(%.1f %.1f) rotate(-90)\" text-anchor=\"middle\">",
                f->left - 54, f->top + f->h / 2);
    html_text(b, "", p->y_label, "</text>\n");
}

/* Dotted lines of each slope through the highest data point (the leftmost of equals), labelled at
   their end: from the largest error they run across the data even when wall times are noisy; a
   label that would overlap one already placed (lines ending close together when the y range is
   narrow) moves up a line. */
static void guides(struct sbuf *b, const struct frame *f, const struct chart_panel *p)
{
    double ax = INFINITY, ay = 0, placed_x[8], placed_y[8], placed_w[8];
    int placed = 0;
    for (int s = 0; s < p->n_series; s++)
        for (int i = 0; i < p->series[s].n; i++) {
            const struct chart_series *se = &p->series[s];
            if (usable(se->x[i]) && usable(se->y[i]) && (se->y[i] > ay || (se->y[i] == ay && se->x[i] < ax)))
                ax = se->x[i], ay = se->y[i];
        }
    for (int g = 0; g < p->n_slopes; g++) {
        double k = p->slopes[g];
        /* From the anchor to where the line leaves the frame (right edge or bottom). */
        double lx0 = log10(ax), ly0 = log10(ay), lx1 = f->r.x1, ly1 = ly0 + k * (lx1 - lx0);
        if (ly1 < f->r.y0) {
            ly1 = f->r.y0;
            lx1 = lx0 + (ly1 - ly0) / k;
        }
        double x0 = px(f, ax), y0 = py(f, ay), x1 = px(f, pow(10, lx1)), y1 = py(f, pow(10, ly1));
        sbuf_printf(
            b,
            "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#777777\" stroke-width=\"1.2\" "
            "stroke-dasharray=\"2 4\"/>\n",
            x0, y0, x1, y1);
        char text[32];
        int len = snprintf(text, sizeof text, "slope %g", k);
        /* right-aligned at (tx, ty), 11 px text: about 6.5 px a character, 12 px high */
        double tx = x1 - 2, ty = y1 - 4, tw = 6.5 * len;
        for (int q = 0; q < placed; q++)
            if (tx - tw < placed_x[q] && placed_x[q] - placed_w[q] < tx && fabs(ty - placed_y[q]) < 13) {
                ty = placed_y[q] - 13;
                q = -1; /* check the new place against every label again */
            }
        if (placed < 8)
            placed_x[placed] = tx, placed_y[placed] = ty, placed_w[placed++] = tw;
        sbuf_printf(
            b,
            "<text x=\"%.1f\" y=\"%.1f\" fill=\"#555555\" font-size=\"11\" text-anchor=\"end\">%s</text>\n",
            tx, ty, text);
    }
}

static void series(struct sbuf *b, const struct frame *f, const struct chart_series *se, const char *color)
{
    sbuf_printf(b, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"2\" points=\"", color);
    for (int i = 0; i < se->n; i++)
        if (usable(se->x[i]) && usable(se->y[i]))
            sbuf_printf(b, "%.1f,%.1f ", px(f, se->x[i]), py(f, se->y[i]));
    sbuf_printf(b, "\"/>\n");
    for (int i = 0; i < se->n; i++) {
        if (!usable(se->x[i]) || !usable(se->y[i]))
            continue;
        double x = px(f, se->x[i]), y = py(f, se->y[i]);
        if (se->lo && se->hi && usable(se->lo[i]) && usable(se->hi[i])) {
            double y0 = py(f, se->lo[i]), y1 = py(f, se->hi[i]);
            sbuf_printf(
                b,
                "<path d=\"M%.1f %.1fV%.1fM%.1f %.1fh8M%.1f %.1fh8\" stroke=\"%s\" stroke-width=\"1.5\"/>\n",
                x, y0, y1, x - 4, y0, x - 4, y1, color);
        }
        sbuf_printf(b, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3\" fill=\"%s\"/>\n", x, y, color);
    }
}

/* The legend column's width: room for the longest entry of any panel (labels may be long). */
static int legend_width(const struct chart_panel *panels, int n)
{
    size_t longest = strlen("whiskers");
    for (int i = 0; i < n; i++)
        if (panels[i].whisker_note && strlen(panels[i].whisker_note) > longest)
            longest = strlen(panels[i].whisker_note);
    for (int i = 0; i < n; i++)
        for (int s = 0; s < panels[i].n_series; s++)
            if (panels[i].series[s].name && strlen(panels[i].series[s].name) > longest)
                longest = strlen(panels[i].series[s].name);
    int w = LEGEND_TEXT_X + CHAR_W * (int)longest + 8 + 12;
    return w > LEGEND_W ? w : LEGEND_W;
}

/* The series of panel p, with their colours, and what the dotted lines and whiskers are. */
static void legend(struct sbuf *b, double x, double y, int legend_w, const struct chart_panel *p)
{
    int whiskers = 0;
    for (int s = 0; s < p->n_series; s++)
        whiskers |= p->series[s].lo && p->series[s].hi;
    int rows = p->n_series + (p->n_slopes > 0) + whiskers;
    sbuf_printf(
        b, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%d\" height=\"%d\" fill=\"#ffffff\" stroke=\"#cccccc\"/>\n",
        x, y, legend_w - 12, 10 + 18 * rows);
    for (int s = 0; s < p->n_series; s++) {
        double ly = y + 18 + 18 * s;
        sbuf_printf(
            b, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"3\"/>\n",
            x + 8, ly - 4, x + 28, ly - 4, series_color(p, s));
        sbuf_printf(b, "<text x=\"%.1f\" y=\"%.1f\">", x + LEGEND_TEXT_X, ly);
        html_text(b, "", p->series[s].name, "</text>\n");
    }
    double ly = y + 18 + 18 * p->n_series;
    if (p->n_slopes > 0) {
        sbuf_printf(b,
                    "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#777777\" "
                    "stroke-dasharray=\"2 4\"/>\n"
                    "<text x=\"%.1f\" y=\"%.1f\">guide slopes</text>\n",
                    x + 8, ly - 4, x + 28, ly - 4, x + LEGEND_TEXT_X, ly);
        ly += 18;
    }
    if (whiskers)
        sbuf_printf(b,
                    "<path d=\"M%.1f %.1fV%.1fM%.1f %.1fh8M%.1f %.1fh8\" stroke=\"#444444\"/>\n<text "
                    "x=\"%.1f\" y=\"%.1f\">%s</text>\n",
                    x + 18, ly - 12, ly + 2, x + 14, ly - 12, x + 14, ly + 2, x + LEGEND_TEXT_X, ly,
                    p->whisker_note ? p->whisker_note : "whiskers");
}

static void panel(struct sbuf *b, const struct chart_panel *p, double ox, double oy)
{
    struct frame f = {ox + MARGIN_L,
                      oy + MARGIN_T,
                      PANEL_W - MARGIN_L - MARGIN_R,
                      PANEL_H - MARGIN_T - MARGIN_B,
                      {0, 0, 0, 0}};
    sbuf_printf(b, "<g>\n<text x=\"%.1f\" y=\"%.1f\" font-weight=\"bold\">", f.left, oy + 20);
    html_text(b, "", p->title, "</text>\n");
    if (!data_range(p, &f.r)) {
        sbuf_printf(b,
                    "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#fafafa\" "
                    "stroke=\"#444444\"/>\n"
                    "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">",
                    f.left, f.top, f.w, f.h, f.left + f.w / 2, f.top + f.h / 2);
        html_text(b, "", p->empty_note ? p->empty_note : "no data", "</text>\n</g>\n");
        return;
    }
    axes(b, &f, p);
    guides(b, &f, p);
    for (int s = 0; s < p->n_series; s++)
        series(b, &f, &p->series[s], series_color(p, s));
    sbuf_printf(b, "</g>\n");
}

char *chart_svg(const char *title, const struct chart_panel *panels, int n, int columns)
{
    struct sbuf b = {0};
    int cols = columns < 1 ? 1 : columns, rows = (n + cols - 1) / cols;
    int legend_w = legend_width(panels, n), w = cols * PANEL_W + legend_w, h = TITLE_H + rows * PANEL_H;
    sbuf_printf(
        &b,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
        "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"%d\" height=\"%d\" fill=\"#ffffff\"/>\n"
        "<text x=\"12\" y=\"22\" font-size=\"15\" font-weight=\"bold\">",
        w, h, w, h, w, h);
    html_text(&b, "", title, "</text>\n");
    for (int i = 0; i < n; i++) {
        panel(&b, &panels[i], (i % cols) * PANEL_W, TITLE_H + (i / cols) * PANEL_H);
        if (i % cols == 0 && panels[i].n_series > 0)
            legend(&b, cols * PANEL_W + 4, TITLE_H + (i / cols) * PANEL_H + MARGIN_T, legend_w, &panels[i]);
    }
    sbuf_printf(&b, "</svg>\n");
    return sbuf_take(&b);
}
