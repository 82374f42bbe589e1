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

/* The digit-permutation hash of one level: the seed, the dimension and the digits above. */
static uint64_t level_hash(const struct zsobol_key *k, uint64_t above)
{
    return rng_mix64(above ^ rng_mix64(k->seed ^ ((uint64_t)k->dim + 1) * 0x9e3779b97f4a7c15ULL));
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

uint64_t zsobol_index(struct zsobol_key k, uint32_t i)
{
    const int odd = k.log2_spp & 1;
    const uint64_t morton = spread_bits(k.x) | spread_bits(k.y) << 1;
    const uint64_t raw = morton << k.log2_spp | (i & (((uint64_t)1 << k.log2_spp) - 1));
    uint64_t out = 0;
    /* digits at bits (shift, shift + 1) from the top (raw uses bits below 32 + log2_spp <= 56);
       an odd log2_spp leaves bit 0 alone, so a Morton digit (a pixel's x and y bit) stays one */
    for (int shift = 32 + k.log2_spp - 2; shift >= odd; shift -= 2) {
        const uint32_t digit = (uint32_t)(raw >> shift) & 3u;
        out |= (uint64_t)permute4(level_hash(&k, raw >> (shift + 2)), digit) << shift;
    }
    if (odd)
        out |= (raw & 1u) ^ (level_hash(&k, raw >> 1) >> 63);
    return out;
}

struct pt2 zsobol_point(struct zsobol_key k, uint32_t i)
{
    const uint64_t index = zsobol_index(k, i);
    const uint32_t lo = (uint32_t)index, hi = (uint32_t)(index >> 32);
    const uint64_t h = rng_mix64(k.seed ^ rng_mix64((uint64_t)k.dim + 0x5a0b01ULL));
    /* Sobol's first coordinate takes an index's low 32 bits only (32 digits); its second's
       generator matrix is Pascal's triangle mod 2, and a column k >= 32 equals column k - 32 in
       the first 32 digits (Lucas's theorem), so the high half adds sobol_y(hi) */
    const uint32_t x = sobol_owen(sobol_x(lo), (uint32_t)h),
                   y = sobol_owen(sobol_y(lo) ^ sobol_y(hi), (uint32_t)(h >> 32));
    return (struct pt2){x * 0x1.0p-32, y * 0x1.0p-32};
}

void zsobol_fill(struct zsobol_key k, struct pt2 *out)
{
    const uint32_t n = (uint32_t)1 << k.log2_spp;
    for (uint32_t i = 0; i < n; i++)
        out[i] = zsobol_point(k, i);
}
