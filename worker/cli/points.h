/* points: the `worker points` subcommand, one sample set as CSV and optionally as an SVG picture. */
#ifndef POINTS_H
#define POINTS_H

/* worker points SAMPLER THRESHOLD [options], with argv[0] = "points": a set's points as CSV on
   stdout, or its statistics, pictures and spectra. The exit status: 0 done, 1 output could not be
   written, 2 bad usage or input (one line on stderr says why). */
int points_main(int argc, char **argv);

#endif
