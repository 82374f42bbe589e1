/* sobol: the Owen-scrambled Sobol (0,2)-sequence, the sobol sampler's points. */
#ifndef SOBOL_H
#define SOBOL_H

#include <stddef.h>
#include <stdint.h>

#include "base/rng.h"
#include "pt2.h"

/* The seeds of one scrambled 2D set: one shuffles the sequence's indices (shared by the pair's two
   dimensions, so the points stay pairs), one scrambles each dimension's digits. */
struct sobol_seeds {
    uint32_t index, x, y;
};

/* The scrambled sequence's building blocks, inline for the callers that make points one at a time
   (sobol.c explains each). */
/* v's 32 bits in reverse order (digit 1 of a binary fraction becomes bit 0). */
static inline uint32_t sobol_bit_reverse(uint32_t v)
{
    v = (v >> 16) | (v << 16);
    v = ((v & 0xff00ff00u) >> 8) | ((v & 0x00ff00ffu) << 8);
    v = ((v & 0xf0f0f0f0u) >> 4) | ((v & 0x0f0f0f0fu) << 4);
    v = ((v & 0xccccccccu) >> 2) | ((v & 0x33333333u) << 2);
    return ((v & 0xaaaaaaaau) >> 1) | ((v & 0x55555555u) << 1);
}

/* Two reversals in one: v's 64 bits in reverse order, so (a << 32 | b) becomes rev(b) << 32 |
   rev(a) (a point's x and y: one byte swap and three mask steps for both, not two of each). */
static inline uint64_t sobol_bit_reverse_pair(uint64_t v)
{
    v = __builtin_bswap64(v);
    v = ((v & 0xf0f0f0f0f0f0f0f0u) >> 4) | ((v & 0x0f0f0f0f0f0f0f0fu) << 4);
    v = ((v & 0xccccccccccccccccu) >> 2) | ((v & 0x3333333333333333u) << 2);
    return ((v & 0xaaaaaaaaaaaaaaaau) >> 1) | ((v & 0x5555555555555555u) << 1);
}

/* Laine and Karras's permutation of a bit-reversed value: adding the seed and xoring products
   with even multipliers flip bit k by a function of the seed and bits below k only, so read
   reversed, digit k of the fraction by the digits above it: an Owen scramble's tree of flips,
   each node's flip given by the hash. */
static inline uint32_t sobol_owen_reversed(uint32_t r, uint32_t seed)
{
    r += seed;
    r ^= r * 0x6c50b47cu;
    r ^= r * 0xb82f1e52u;
    r ^= r * 0xc7afe638u;
    r ^= r * 0x8d22f6e6u;
    return r;
}

/* Sobol's second dimension before its final bit reversal. Its generator matrix is Pascal's
   triangle mod 2 (direction numbers v_1 = 1/2, v_(k+1) = v_k xor v_k / 2): digit j + 1 of the
   fraction is the xor of the index bits k with C(k, j) odd, which by Lucas's theorem are the k
   whose bits include j's. That xor over supersets is five shift-and-mask steps, one per bit of
   j (a subset-sum transform over GF(2)); the result holds digit j + 1 in bit j. */
static inline uint32_t sobol_y_reversed(uint32_t i)
{
    i ^= (i >> 1) & 0x55555555u;
    i ^= (i >> 2) & 0x33333333u;
    i ^= (i >> 4) & 0x0f0f0f0fu;
    i ^= (i >> 8) & 0x00ff00ffu;
    i ^= (i >> 16) & 0x0000ffffu;
    return i;
}

/* The point whose reversed, unscrambled coordinates are xr and yr, each Owen-scrambled with its
   seed: both coordinates are bit reversals of a reversed value, so each costs one reversal,
   both done as one 64-bit. */
static inline struct pt2 sobol_scrambled_pair(uint32_t xr, uint32_t yr, uint32_t seed_x, uint32_t seed_y)
{
    const uint64_t yx = sobol_bit_reverse_pair((uint64_t)sobol_owen_reversed(xr, seed_x) << 32 |
                                               sobol_owen_reversed(yr, seed_y));
    const uint32_t x = (uint32_t)yx, y = (uint32_t)(yx >> 32);
    return (struct pt2){x * 0x1.0p-32, y * 0x1.0p-32};
}

/* Point k: index i = owen(k) (Burley's shuffle: the first 2^m shuffled indices are one aligned
   block of 2^m Sobol indices, itself a (0,m,2)-net), then x = owen(sobol_x(i)) and y =
   owen(sobol_y(i)), each with its own seed; Owen scrambling keeps a net a net. sobol_point's
   body. */
static inline struct pt2 sobol_point_inline(struct sobol_seeds s, uint32_t k)
{
    const uint32_t i = sobol_bit_reverse(sobol_owen_reversed(sobol_bit_reverse(k), s.index));
    return sobol_scrambled_pair(i, sobol_y_reversed(i), s.x, s.y);
}

/* A set's points of index below 2^bits, made one at a time (padding's Sobol slots), split in what
   is fixed per set and what varies per point. Index k's reversal rev(k) has its bits in the top
   `bits` only, and sobol_owen_reversed changes bit j by the bits below it alone, so the low 32 -
   bits bits of owen_reversed(rev(k)) are the seed's alone: the shuffled index i = rev(that) is a
   fixed high part (xr_hi) or a low part of `bits` bits read from owen_reversed's top bits. Sobol's
   second dimension is linear over GF(2), so its reversed value is yr_hi = sobol_y_reversed(xr_hi)
   xor the low part's (tabled with it). The point is sobol_point's, bit for bit, for one hash and a
   table lookup instead of two reversals and the second dimension's five steps. */
struct sobol_block {
    uint32_t index;   /* the index shuffle's seed */
    uint32_t seed[2]; /* x's and y's scramble seeds */
    uint32_t hi[2];   /* the shuffled index's fixed high part, as x's and y's reversed values */
};

/* The fixed part of seeds s's points below 2^bits (1 <= bits <= 31). */
static inline struct sobol_block sobol_block_of(struct sobol_seeds s, int bits)
{
    const uint32_t hi = sobol_bit_reverse(sobol_owen_reversed(0, s.index)) & ~((1u << bits) - 1);
    return (struct sobol_block){s.index, {s.x, s.y}, {hi, sobol_y_reversed(hi)}};
}

/* The low parts' table for bits (1 <= bits <= 31): entry v is the index's low part rev(v) read as
   a `bits`-bit value, and its second dimension reversed in the high 32 bits; 2^bits entries. */
void sobol_low_table(uint64_t *table, int bits);

/* Point k of b's set (k < 2^bits) from rev(k) (sobol_bit_reverse), table = sobol_low_table(bits):
   sobol_point(seeds, k) of the seeds b was made from, bit for bit. */
static inline struct pt2 sobol_block_point(const struct sobol_block *b, const uint64_t *table, int bits,
                                           uint32_t k_reversed)
{
    const uint64_t low = table[sobol_owen_reversed(k_reversed, b->index) >> (32 - bits)];
    return sobol_scrambled_pair(b->hi[0] | (uint32_t)low, b->hi[1] ^ (uint32_t)(low >> 32), b->seed[0],
                                b->seed[1]);
}

/* sobol_block_point with AVX2, the same bits: both coordinates' hashes, bit reversals (a byte
   shuffle and two nibble lookups) and conversions side by side in one register. Only where
   simd_avx2() (base/simd.h) says so; without SIMD_AVX2 it is sobol_block_point. */
struct pt2 sobol_block_point_wide(const struct sobol_block *b, const uint64_t *table, int bits,
                                  uint32_t k_reversed);

/* The seeds of the next set, three draws of rng: a set per (seed, pixel) and per dimension pair,
   whatever the caller's rng is seeded from. */
struct sobol_seeds sobol_seeds_draw(struct rng *rng);

/* The unscrambled sequence's i-th point as 32-bit binary fractions: x the van der Corput radical
   inverse in base 2, y Sobol's second dimension. */
uint32_t sobol_x(uint32_t i);
uint32_t sobol_y(uint32_t i);

/* Owen's nested uniform scramble of v's binary digits (digit 1 the most significant bit): each
   digit flipped or not by a hash of seed and the digits above it. A bijection of 32-bit values. */
uint32_t sobol_owen(uint32_t v, uint32_t seed);

/* The first n points of the scrambled sequence for seeds s, into out (n <= 2^32). The first 2^m
   points form a (0,m,2)-net for every m; other n are a prefix of one, still stratified at every
   power of two below n. Allocates nothing; cannot fail. */
void sobol_fill(struct sobol_seeds s, size_t n, struct pt2 *out);

/* Point k alone of the scrambled sequence for seeds s: sobol_fill's out[k], bit for bit (for a
   caller that takes a few points of a large set, in any order). Cannot fail. */
struct pt2 sobol_point(struct sobol_seeds s, uint32_t k);

/* The point of a 64-bit index of the unscrambled sequence, each coordinate Owen-scrambled with
   its seed (no index shuffle): x owen(sobol_x(low 32 bits)), y owen(Sobol's second dimension of
   all 64 bits) as sobol_owen would, in one call. Cannot fail. */
struct pt2 sobol_point64(uint64_t index, uint32_t seed_x, uint32_t seed_y);

#endif
