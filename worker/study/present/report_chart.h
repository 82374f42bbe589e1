/* report_chart: chart.svg of a compare job: per scene, relMSE against CPU time and against samples
   per pixel, the seeds' means with whiskers from the best to the worst seed. */
#ifndef REPORT_CHART_H
#define REPORT_CHART_H

#include "study/load/compare_model.h"

/* The chart as a malloc'd SVG document (caller frees), NULL when out of memory. */
char *report_chart_svg(const struct compare *c);

#endif
