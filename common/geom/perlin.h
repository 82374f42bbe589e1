/* perlin: gradient noise and turbulence (Perlin 1985/2002, as in RTOW "The Next Week"). */
#ifndef PERLIN_H
#define PERLIN_H

#include <stdint.h>

#include "base/vec3.h"

#define PERLIN_N 256

/* A gradient table: unit vectors and three permutations, all from one seed; the same again as
   the noise reads them: the vectors padded to four doubles in one flat array and the
   permutations as offsets into it (4 perm: XORed together they are the offset of the XORed
   index), each with its first entry repeated at the end (a cell's far corner without a wrap). */
struct perlin {
    vec3 ranvec[PERLIN_N];
    int perm_x[PERLIN_N], perm_y[PERLIN_N], perm_z[PERLIN_N];
    double grad[4 * PERLIN_N];
    unsigned off_x[PERLIN_N + 1], off_y[PERLIN_N + 1], off_z[PERLIN_N + 1];
};

/* The seed every scene's noise table uses, so a scene renders the same everywhere. */
#define PERLIN_SEED 0x6e6f697365ULL

/* Fill p from seed (deterministic). Never fails. */
void perlin_init(struct perlin *p, uint64_t seed);

/* Smooth noise in about [-1, 1] at point q. */
double perlin_noise(const struct perlin *p, vec3 q);

/* |sum of depth octaves of noise|, each at twice the frequency and half the weight. */
double perlin_turb(const struct perlin *p, vec3 q, int depth);

#endif
