/* points: the `worker points` subcommand, one sample set as CSV and optionally as an SVG picture. */
#ifndef POINTS_H
#define POINTS_H

/* worker points SAMPLER THRESHOLD [--seed S] [--svg F], with argv[0] = "points". Prints a header
   line "x,y" and one "x,y" line per point (6 decimals, in [0, 1)) to stdout; --svg also writes
   the set as an SVG file, atomically. Returns the exit status: 0 done, 1 output could not be
   written, 2 bad usage or input (one line on stderr says why). */
int points_main(int argc, char **argv);

#endif
