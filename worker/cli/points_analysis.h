/* points_analysis: `worker points`'s --spectrum, --radial and --stats over --sets sets. */
#ifndef POINTS_ANALYSIS_H
#define POINTS_ANALYSIS_H

#include <stddef.h>
#include <stdint.h>

#include "sample/sampler.h"

struct points_analysis {
    const char *spectrum_path; /* NULL: no periodogram picture */
    const char *radial_path;   /* NULL: no radial chart */
    int stats;                 /* print the statistics on stdout */
    int sets;                  /* M >= 1: seeds seed .. seed + M - 1 */
    uint64_t seed;
    double threshold;
};

/* Whether any analysis is asked for. */
int points_analysis_wanted(const struct points_analysis *a);

/* Check the work the analysis asks for against its limits, for sets of about n points: 0, or 2
   after one line on stderr naming the work, the limit and what to change. */
int points_analysis_check(const struct points_analysis *a, size_t n);

/* Draw the M sets with s (buf holds sampler_set_capacity(s) points), write the pictures and print
   the statistics asked for. The exit status: 0, or 1 after one line on stderr. */
int points_analysis_run(const struct points_analysis *a, struct sampler *s, struct pt2 *buf);

#endif
