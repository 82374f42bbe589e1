/* poisson: Bridson's fast Poisson-disk point sets, the workspace behind the poisson sampler. */
#ifndef POISSON_H
#define POISSON_H

#include <stddef.h>
#include <stdint.h>

#include "base/rng.h"
#include "pt2.h"

/* Candidate offsets drawn ahead in one batch (a multiple of 4). */
#define POISSON_OFFSETS 64

/* A background grid and active list sized once for one minimum distance, reused by every draw. */
struct poisson {
    double radius;    /* minimum distance r */
    int side;         /* background grid: side x side cells of size 1/side <= r/sqrt(2) */
    int pad;          /* cells of margin around it, so a neighbourhood never leaves the array */
    int window;       /* cells per axis that cover [c - r, c + r] wherever c falls */
    size_t stride;    /* side + 2 pad */
    int32_t *cell;    /* stride^2: index of the sample in a cell, -1 when empty */
    int16_t *cell_uv; /* 2 stride^2: that sample's (u, v) offset inside its cell, fixed point */
    int32_t *active;  /* Bridson's active list: indices into the set being drawn */
    float off_x[POISSON_OFFSETS], off_y[POISSON_OFFSETS]; /* candidate offsets drawn ahead, in r */
};

/* Size the workspace for minimum distance radius, a grid of side cells per axis
   (1/side <= radius/sqrt 2) and sets of at most capacity points. 0, or -1 on no memory
   (nothing left to release). */
int poisson_init(struct poisson *p, double radius, int side, size_t capacity);
void poisson_release(struct poisson *p);

/* Draw one maximal set with minimum distance radius into out (capacity points), consuming rng;
   torus != 0 measures distances modulo 1. Returns the count. Allocates nothing. */
size_t poisson_draw(struct poisson *p, struct rng *rng, struct pt2 *out, int torus);

#endif
