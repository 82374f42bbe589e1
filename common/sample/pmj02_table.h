/* pmj02_table: a few pmj02bn sequences drawn once by our own generator (pmj02.c) at build time:
   tools/gen_pmj02.c writes them into a generated source (build/gen/pmj02_table.c, `make`), as
   pbrt-v4 keeps its pmj02bn tables (Pharr, Jakob and Humphreys, PBR 4th ed., 8.5). A set of the
   pmj02bn sampler is then a prefix of one of them, picked at random, with its binary digits
   flipped by a random mask per coordinate (a digital shift: a (0,m,2)-net stays one, and every
   point is uniform), instead of a fresh sequence per pixel and dimension. */
#ifndef PMJ02_TABLE_H
#define PMJ02_TABLE_H

#include <stdint.h>

#include "pt2.h"

/* How many sequences, and their length: 2^14 points, the sets of thresholds down to 1 (larger
   sets are drawn fresh, as before). */
#define PMJ02_TABLE_SETS 4u
#define PMJ02_TABLE_LOG2 14
#define PMJ02_TABLE_POINTS (1u << PMJ02_TABLE_LOG2)
/* Sequence i is pmj02_draw's for rng_seed(&r, PMJ02_TABLE_SEED, i), as 32-bit binary fractions. */
#define PMJ02_TABLE_SEED 0x706d6a3032626eULL

/* The sequences: pmj02_table[i][k] is point k of sequence i, x then y (generated source). */
extern const uint32_t pmj02_table[PMJ02_TABLE_SETS][PMJ02_TABLE_POINTS][2];

/* The first n points (n <= PMJ02_TABLE_POINTS) of sequence `set`, x xor fx and y xor fy, into
   out. Cannot fail. */
static inline void pmj02_table_fill(uint32_t set, uint32_t fx, uint32_t fy, uint32_t n, struct pt2 *out)
{
    const uint32_t(*seq)[2] = pmj02_table[set];
    for (uint32_t k = 0; k < n; k++)
        out[k] = (struct pt2){(seq[k][0] ^ fx) * 0x1.0p-32, (seq[k][1] ^ fy) * 0x1.0p-32};
}

#endif
