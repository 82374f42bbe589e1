/* points: the `worker points` subcommand, one sample set as CSV and optionally as an SVG picture. */
#ifndef POINTS_H
#define POINTS_H

/* worker points SAMPLER THRESHOLD [--seed S] [--sets M] [--svg F] [--spectrum F.png] [--radial F.svg]
   [--stats], with argv[0] = "points". Prints one "x,y" line per point of seed S's set (6 decimals,
   in [0, 1)) to stdout, or with --stats the statistics instead (count, minimum distance plain and
   toroidal, L2 star discrepancy, low-frequency power), one "name value (what)" line each; --svg
   draws seed S's set; --spectrum and --radial write the mean periodogram and its radial mean and
   anisotropy; --sets M averages the analyses over seeds S .. S + M - 1. Files are written
   atomically. Returns the exit status: 0 done, 1 output could not be
   written, 2 bad usage or input (one line on stderr says why). */
int points_main(int argc, char **argv);

#endif
