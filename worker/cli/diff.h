/* diff: the `worker diff` subcommand, error metrics of an image against a reference. */
#ifndef DIFF_H
#define DIFF_H

/* worker diff A B [--json] [--map F.png] [--max-rmse X] [--block N], with argv[0] = "diff". A is
   the reference; each of A and B may be EXR, PFM, PNG or PPM. Prints mse, rmse, relmse,
   relmse_robust, psnr and the domain measured in (linear when both are float images, else 8-bit
   display values) as lines, or with --json as one JSON object; --map writes a false-colour PNG of
   the per-pixel relative error (its scale in a tEXt chunk). Returns the exit status: 0, 1 when
   rmse is over --max-rmse, 2 bad usage or input (one line on stderr says why). */
int diff_main(int argc, char **argv);

#endif
