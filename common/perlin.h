/* perlin: gradient noise and turbulence (Perlin 1985/2002, as in RTOW "The Next Week"). */
#ifndef PERLIN_H
#define PERLIN_H

#include <stdint.h>

#include "vec3.h"

#define PERLIN_N 256

/* A gradient table: unit vectors and three permutations, all from one seed. */
struct perlin {
    vec3 ranvec[PERLIN_N];
    int perm_x[PERLIN_N], perm_y[PERLIN_N], perm_z[PERLIN_N];
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
