/* zsobol: Z-Sobol points (Ahmed and Wonka 2020): a Morton index per pixel, its base-4 digits
   permuted hierarchically, into one Owen-scrambled Sobol sequence per dimension (sobol.h's). */
#include "zsobol.h"

#include "sobol.h"

/* Bits 0..15 of v spread to the even bits of the result. */
static uint64_t spread_bits(uint32_t v)
{
    uint64_t x = v & 0xffffu;
    x = (x | x << 8) & 0x00ff00ffu;
    x = (x | x << 4) & 0x0f0f0f0fu;
    x = (x | x << 2) & 0x33333333u;
    return (x | x << 1) & 0x55555555u;
}

/* The 24 permutations of {0,1,2,3} in lexicographic order (row p: Lehmer code p / 6, p / 2 mod 3,
   p mod 2): a lookup instead of decoding the code per digit. */
static const uint8_t perms4[24][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 1, 3}, {0, 2, 3, 1}, {0, 3, 1, 2},
                                      {0, 3, 2, 1}, {1, 0, 2, 3}, {1, 0, 3, 2}, {1, 2, 0, 3}, {1, 2, 3, 0},
                                      {1, 3, 0, 2}, {1, 3, 2, 0}, {2, 0, 1, 3}, {2, 0, 3, 1}, {2, 1, 0, 3},
                                      {2, 1, 3, 0}, {2, 3, 0, 1}, {2, 3, 1, 0}, {3, 0, 1, 2}, {3, 0, 2, 1},
                                      {3, 1, 0, 2}, {3, 1, 2, 0}, {3, 2, 0, 1}, {3, 2, 1, 0}};

/* The permutation (a row of perms4) numbered by hash h. */
static inline const uint8_t *perm_of(uint64_t h)
{
    return perms4[(uint32_t)(h >> 40) % 24u];
}

/* The digits of raw at shifts from `from` down to `to` (step 2), each permuted by the hash of
   key (the seed and dimension, mixed once) and the digits above it. */
static uint64_t permute_digits(uint64_t key, uint64_t raw, int from, int to)
{
    uint64_t out = 0;
    for (int shift = from; shift >= to; shift -= 2) {
        const uint32_t digit = (uint32_t)(raw >> shift) & 3u;
        out |= (uint64_t)perm_of(rng_mix64((raw >> (shift + 2)) ^ key))[digit] << shift;
    }
    return out;
}

/* What a pixel's samples share: the hash key, the raw index of sample 0 and its permuted pixel
   digits (those at bit log2_spp and above: the Morton code's alone). */
struct pixel_block {
    uint64_t key, raw, high;
};

static struct pixel_block block_of(const struct zsobol_key *k)
{
    struct pixel_block b;
    b.key = rng_mix64(k->seed ^ ((uint64_t)k->dim + 1) * 0x9e3779b97f4a7c15ULL);
    b.raw = (spread_bits(k->x) | spread_bits(k->y) << 1) << k->log2_spp;
    /* digits at bits (shift, shift + 1) from the top (raw uses bits below 32 + log2_spp <= 56); an
       odd log2_spp leaves bit 0 alone, so a Morton digit (a pixel's x and y bit) stays one */
    b.high = permute_digits(b.key, b.raw, 32 + k->log2_spp - 2, k->log2_spp);
    return b;
}

static uint64_t index_in(const struct pixel_block *b, int log2_spp, uint32_t i)
{
    const int odd = log2_spp & 1;
    const uint64_t raw = b->raw | (i & (((uint64_t)1 << log2_spp) - 1));
    uint64_t out = b->high | permute_digits(b->key, raw, log2_spp - 2, odd);
    if (odd)
        out |= (raw & 1u) ^ (rng_mix64((raw >> 1) ^ b->key) >> 63);
    return out;
}

uint64_t zsobol_index(struct zsobol_key k, uint32_t i)
{
    const struct pixel_block b = block_of(&k);
    return index_in(&b, k.log2_spp, i);
}

/* The scrambled Sobol point of a 64-bit index, scramble seeds from h (sobol_point64). */
static inline struct pt2 point_at(uint64_t index, uint64_t h)
{
    return sobol_point64(index, (uint32_t)h, (uint32_t)(h >> 32));
}

static uint64_t scramble_seeds(const struct zsobol_key *k)
{
    return rng_mix64(k->seed ^ rng_mix64((uint64_t)k->dim + 0x5a0b01ULL));
}

struct pt2 zsobol_point(struct zsobol_key k, uint32_t i)
{
    return point_at(zsobol_index(k, i), scramble_seeds(&k));
}

/* A set's filling: the pixel's hash key, the scramble seeds, whether log2_spp is odd, where the
   next point goes. */
struct filling {
    uint64_t key, h;
    int odd;
    struct pt2 *out;
};

/* The points of the indices below raw's digits above bit shift + 2 (raw unpermuted, index its
   permuted image), in order: the digit at shift is permuted by the hash of those above it, once
   for its four values, then each value's digits below the same way (index_in's bits). */
static void descend(struct filling *f, uint64_t raw, uint64_t index, int shift)
{
    const uint8_t *perm = perm_of(rng_mix64((raw >> (shift + 2)) ^ f->key));
    for (uint32_t d = 0; d < 4; d++) {
        const uint64_t r = raw | (uint64_t)d << shift, x = index | (uint64_t)perm[d] << shift;
        if (shift > f->odd) {
            descend(f, r, x, shift - 2);
        } else if (f->odd) { /* the lone lowest bit, flipped by the hash of the bits above */
            const uint64_t lone = rng_mix64((r >> 1) ^ f->key) >> 63;
            *f->out++ = point_at(x | lone, f->h);
            *f->out++ = point_at(x | (1u ^ lone), f->h);
        } else {
            *f->out++ = point_at(x, f->h);
        }
    }
}

/* All of the block's points in order, index_in's for i = 0, 1, ...: a digit's permutation depends
   on the digits above it only, so it is hashed once per run of samples that share them (1 + 4 +
   16 + ... hashes for the set, not one per digit and point). */
void zsobol_fill(struct zsobol_key k, struct pt2 *out)
{
    const struct pixel_block b = block_of(&k);
    struct filling f = {b.key, scramble_seeds(&k), k.log2_spp & 1, out};
    if (k.log2_spp >= 2) {
        descend(&f, b.raw, b.high, k.log2_spp - 2);
    } else if (k.log2_spp == 1) {
        const uint64_t lone = rng_mix64((b.raw >> 1) ^ b.key) >> 63;
        out[0] = point_at(b.high | lone, f.h);
        out[1] = point_at(b.high | (1u ^ lone), f.h);
    } else {
        out[0] = point_at(b.high, f.h);
    }
}
