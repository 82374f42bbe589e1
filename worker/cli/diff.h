/* diff: the `worker diff` subcommand, error metrics of an image against a reference. */
#ifndef DIFF_H
#define DIFF_H

/* worker diff A B [options] (its --help lists them), with argv[0] = "diff": B's error figures
   against the reference A printed. The exit status: 0, 1 when rmse is over --max-rmse, 2 bad
   usage or input (one line on stderr says why). */
int diff_main(int argc, char **argv);

#endif
