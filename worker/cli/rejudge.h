/* rejudge: the `worker verdict` subcommand, a finished compare output folder judged again. */
#ifndef REJUDGE_H
#define REJUDGE_H

/* worker verdict DIR [--json], with argv[0] = "verdict": the verdict of the study or suite whose
   output folder is DIR printed (its --help says from what), writing nothing. The exit status: 0,
   or 2 on bad usage or input (one line on stderr says why). */
int rejudge_main(int argc, char **argv);

#endif
