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

/* digit's image under the permutation of {0,1,2,3} numbered h mod 24 (its Lehmer code). */
static uint32_t permute4(uint64_t h, uint32_t digit)
{
    uint32_t p = (uint32_t)(h >> 40) % 24u, left[4] = {0, 1, 2, 3}, image[4];
    const uint32_t code[3] = {p / 6, (p / 2) % 3, p % 2};
    int n = 4;
    for (int j = 0; j < 3; j++) {
        image[j] = left[code[j]];
        for (uint32_t t = code[j]; t + 1 < (uint32_t)n; t++)
            left[t] = left[t + 1];
        n--;
    }
    image[3] = left[0];
    return image[digit];
}

/* The digits of raw at shifts from `from` down to `to` (step 2), each permuted by the hash of
   key (the seed and dimension, mixed once) and the digits above it. */
static uint64_t permute_digits(uint64_t key, uint64_t raw, int from, int to)
{
    uint64_t out = 0;
    for (int shift = from; shift >= to; shift -= 2) {
        const uint32_t digit = (uint32_t)(raw >> shift) & 3u;
        out |= (uint64_t)permute4(rng_mix64((raw >> (shift + 2)) ^ key), digit) << shift;
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

/* The scrambled Sobol point of a 64-bit index, scramble seeds from h. */
static struct pt2 point_at(uint64_t index, uint64_t h)
{
    const uint32_t lo = (uint32_t)index, hi = (uint32_t)(index >> 32);
    /* Sobol's first coordinate takes an index's low 32 bits only (32 digits); its second's
       generator matrix is Pascal's triangle mod 2, and a column k >= 32 equals column k - 32 in
       the first 32 digits (Lucas's theorem), so the high half adds sobol_y(hi) */
    const uint32_t x = sobol_owen(sobol_x(lo), (uint32_t)h),
                   y = sobol_owen(sobol_y(lo) ^ sobol_y(hi), (uint32_t)(h >> 32));
    return (struct pt2){x * 0x1.0p-32, y * 0x1.0p-32};
}

static uint64_t scramble_seeds(const struct zsobol_key *k)
{
    return rng_mix64(k->seed ^ rng_mix64((uint64_t)k->dim + 0x5a0b01ULL));
}

struct pt2 zsobol_point(struct zsobol_key k, uint32_t i)
{
    return point_at(zsobol_index(k, i), scramble_seeds(&k));
}

void zsobol_fill(struct zsobol_key k, struct pt2 *out)
{
    const struct pixel_block b = block_of(&k);
    const uint64_t h = scramble_seeds(&k);
    const uint32_t n = (uint32_t)1 << k.log2_spp;
    for (uint32_t i = 0; i < n; i++)
        out[i] = point_at(index_in(&b, k.log2_spp, i), h);
}
