/* verdict_points: what an image's name in summary.csv says of its sweep point
   (<scene>-<variant>-t<threshold>[-<key><value>...]-s<seed>.<ext>, compare_expand.c's names). */
#ifndef VERDICT_POINTS_H
#define VERDICT_POINTS_H

#include <stddef.h>

/* The length of a point's key: the image name without "-s<seed>.<ext>" (what the sweep adds stays:
   -t20-lt10-pool64). */
size_t verdict_point_key_len(const char *image);

/* The spp of a point swept in samples per pixel (the last "-spp<N>" of the key's len bytes: each
   variant's own threshold gave it), else 0. */
long verdict_point_spp(const char *key, size_t len);

#endif
