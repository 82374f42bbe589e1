/* chart: a small SVG writer for log-log line charts with whiskers, legends and guide slopes. */
#ifndef CHART_H
#define CHART_H

/* One line: n points (x[i], y[i]) joined in order, each with a whisker from lo[i] to hi[i]
   (lo/hi may be NULL). Points with a non-positive or non-finite coordinate are skipped. */
struct chart_series {
    const char *name;
    int n;
    const double *x, *y, *lo, *hi;
};

/* One log-log panel. Guide slopes (e.g. -1 and -1.5) are drawn dotted through the highest
   data point and labelled. With no drawable point the panel shows `empty_note`. */
struct chart_panel {
    const char *title, *x_label, *y_label, *empty_note;
    const struct chart_series *series;
    int n_series;
    const double *slopes;
    int n_slopes;
    const char *whisker_note; /* the legend's words for the whiskers ("whisker: 95% CI"); NULL: "whiskers" */
};

/* An SVG document (UTF-8, valid XML) with `title` above n panels laid out in `columns`
   columns. A series' colour follows its name (a hash into the palette, the next free slot on
   a clash), so a variant keeps its colour across panels and studies. Returns a
   malloc'd string (caller frees), NULL on no memory. */
char *chart_svg(const char *title, const struct chart_panel *panels, int n, int columns);

/* The colour series i is drawn in ("#1f77b4"), for legends elsewhere (the report). */
const char *chart_color(int i);

#endif
