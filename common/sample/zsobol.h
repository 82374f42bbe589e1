/* zsobol: Z-Sobol points (Ahmed and Wonka 2020, "Screen-Space Blue-Noise Diffusion of Monte Carlo
   Sampling Error via Hierarchical Ordering of Pixels", SIGGRAPH Asia): one Owen-scrambled Sobol
   sequence per dimension for the whole image, each pixel taking one aligned block of it, the
   blocks dealt along a randomly permuted Morton (Z) curve of the pixels. */
#ifndef ZSOBOL_H
#define ZSOBOL_H

#include <stddef.h>
#include <stdint.h>

#include "base/rng.h"
#include "pt2.h"

/* Pixels and samples per pixel a key can address: x, y < 2^16, 2^log2_spp samples with
   log2_spp <= ZSOBOL_MAX_LOG2_SPP. */
#define ZSOBOL_MAX_LOG2_SPP 24

/* Where one pixel's set lies in the sequences: the job's seed, the 2D dimension (the pixel's
   camera point is dimension 0, every further decision its own), the pixel, the set's size. */
struct zsobol_key {
    uint64_t seed;
    uint32_t dim;
    uint32_t x, y;
    int log2_spp;
};

/* The global index of sample i (< 2^log2_spp) of k's pixel: the pixel's Morton code, then i, as
   base-4 digits (a lone lowest bit when log2_spp is odd), each digit permuted by a hash of the
   seed, the dimension and the digits above it. The pixel's 2^log2_spp indices are one aligned
   block; neighbouring pixels' blocks lie together in larger aligned blocks. Cannot fail. */
uint64_t zsobol_index(struct zsobol_key k, uint32_t i);

/* The Sobol point (dimensions 1 and 2) of a 64-bit index as 32-bit binary fractions, each
   coordinate Owen-scrambled with seeds of (seed, dim) alone: one scramble for the whole image. */
struct pt2 zsobol_point(struct zsobol_key k, uint32_t i);

/* The pixel's whole set, 2^log2_spp points: a scrambled (0, log2_spp, 2)-net. Cannot fail. */
void zsobol_fill(struct zsobol_key k, struct pt2 *out);

#endif
