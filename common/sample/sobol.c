/* sobol: the Owen-scrambled Sobol (0,2)-sequence, the sobol sampler's points.

   The construction follows Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)): the
   point of index i is the Sobol point of a shuffled index, each of its coordinates then Owen-
   scrambled, both by the hash Laine and Karras 2011 ("Stratified sampling for stochastic
   transparency", EGSR) use for a nested uniform scramble. Written here from the papers'
   descriptions; the hash's multipliers are the ones Burley lists. */
#include "sobol.h"

#include <string.h>

#include "base/simd.h"

#if SIMD_AVX2
#include <immintrin.h>
#endif

uint32_t sobol_x(uint32_t i)
{
    return sobol_bit_reverse(i);
}

uint32_t sobol_y(uint32_t i)
{
    return sobol_bit_reverse(sobol_y_reversed(i));
}

uint32_t sobol_owen(uint32_t v, uint32_t seed)
{
    return sobol_bit_reverse(sobol_owen_reversed(sobol_bit_reverse(v), seed));
}

struct sobol_seeds sobol_seeds_draw(struct rng *rng)
{
    struct sobol_seeds s;
    s.index = rng_u32(rng);
    s.x = rng_u32(rng);
    s.y = rng_u32(rng);
    return s;
}

/* Sobol's first coordinate takes an index's low 32 bits only (32 digits); its second's generator
   matrix is Pascal's triangle mod 2, and a column k >= 32 equals column k - 32 in the first 32
   digits (Lucas's theorem), so the high half adds its own sobol_y. */
struct pt2 sobol_point64(uint64_t index, uint32_t seed_x, uint32_t seed_y)
{
    const uint32_t lo = (uint32_t)index, hi = (uint32_t)(index >> 32);
    return sobol_scrambled_pair(lo, sobol_y_reversed(lo) ^ sobol_y_reversed(hi), seed_x, seed_y);
}

void sobol_low_table(uint64_t *table, int bits)
{
    for (uint32_t v = 0; v < 1u << bits; v++) {
        const uint32_t low = sobol_bit_reverse(v << (32 - bits));
        table[v] = (uint64_t)sobol_y_reversed(low) << 32 | low;
    }
}

#if SIMD_AVX2
/* The constants of sobol_block_point_wide, each a whole register's worth (loaded, not built). */
static const uint32_t wide_mult[4][4]
    __attribute__((aligned(16))) = {{0x6c50b47cu, 0x6c50b47cu, 0x6c50b47cu, 0x6c50b47cu},
                                    {0xb82f1e52u, 0xb82f1e52u, 0xb82f1e52u, 0xb82f1e52u},
                                    {0xc7afe638u, 0xc7afe638u, 0xc7afe638u, 0xc7afe638u},
                                    {0x8d22f6e6u, 0x8d22f6e6u, 0x8d22f6e6u, 0x8d22f6e6u}};
/* each lane's bytes in reverse order; a byte's low nibble reversed into its high nibble, its high
   nibble reversed into its low; the low nibbles; the top bits */
static const uint8_t wide_bytes[5][16] __attribute__((aligned(16))) = {
    {3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12},
    {0x00, 0x80, 0x40, 0xc0, 0x20, 0xa0, 0x60, 0xe0, 0x10, 0x90, 0x50, 0xd0, 0x30, 0xb0, 0x70, 0xf0},
    {0x0, 0x8, 0x4, 0xc, 0x2, 0xa, 0x6, 0xe, 0x1, 0x9, 0x5, 0xd, 0x3, 0xb, 0x7, 0xf},
    {0xf, 0xf, 0xf, 0xf, 0xf, 0xf, 0xf, 0xf, 0xf, 0xf, 0xf, 0xf, 0xf, 0xf, 0xf, 0xf},
    {0, 0, 0, 0x80, 0, 0, 0, 0x80, 0, 0, 0, 0x80, 0, 0, 0, 0x80}};
static const double wide_scale[2][2]
    __attribute__((aligned(16))) = {{0x1.0p31, 0x1.0p31}, {0x1.0p-32, 0x1.0p-32}};

/* Lane 0 x, lane 1 y: the reversed values xr | low and yr ^ low (xr's low bits are zero, so both
   are one xor of the pair with the table's entry), plus their seeds, through the four multiply-xor
   steps; each lane's bytes reversed by a byte shuffle and each byte's bits by two nibble tables;
   then the unsigned values to doubles (signed after flipping the top bit, 2^31 added back: exact). */
__attribute__((target("avx2"))) struct pt2
sobol_block_point_wide(const struct sobol_block *b, const uint64_t *table, int bits, uint32_t k_reversed)
{
    const uint64_t low = table[sobol_owen_reversed(k_reversed, b->index) >> (32 - bits)];
    uint64_t hi, seed;
    memcpy(&hi, b->hi, sizeof hi);
    memcpy(&seed, b->seed, sizeof seed);
    __m128i v = _mm_add_epi32(_mm_cvtsi64_si128((long long)(hi ^ low)), _mm_cvtsi64_si128((long long)seed));
    /* the tables' addresses hidden from the compiler (an empty asm): GCC otherwise rebuilds each
       constant it can see from immediates, three instructions where a load folds into its use */
    const __m128i *mult = (const __m128i *)(const void *)wide_mult,
                  *bytes = (const __m128i *)(const void *)wide_bytes;
    const double *scale = &wide_scale[0][0];
    __asm__("" : "+r"(mult), "+r"(bytes), "+r"(scale));
    v = _mm_xor_si128(v, _mm_mullo_epi32(v, _mm_load_si128(&mult[0])));
    v = _mm_xor_si128(v, _mm_mullo_epi32(v, _mm_load_si128(&mult[1])));
    v = _mm_xor_si128(v, _mm_mullo_epi32(v, _mm_load_si128(&mult[2])));
    v = _mm_xor_si128(v, _mm_mullo_epi32(v, _mm_load_si128(&mult[3])));
    v = _mm_shuffle_epi8(v, _mm_load_si128(&bytes[0]));
    const __m128i nibble = _mm_load_si128(&bytes[3]);
    v = _mm_or_si128(
        _mm_shuffle_epi8(_mm_load_si128(&bytes[1]), _mm_and_si128(v, nibble)),
        _mm_shuffle_epi8(_mm_load_si128(&bytes[2]), _mm_and_si128(_mm_srli_epi16(v, 4), nibble)));
    __m128d d = _mm_cvtepi32_pd(_mm_xor_si128(v, _mm_load_si128(&bytes[4])));
    d = _mm_mul_pd(_mm_add_pd(d, _mm_load_pd(scale)), _mm_load_pd(scale + 2));
    struct pt2 out;
    _mm_storeu_pd(&out.x, d);
    return out;
}
#else
struct pt2 sobol_block_point_wide(const struct sobol_block *b, const uint64_t *table, int bits,
                                  uint32_t k_reversed)
{
    return sobol_block_point(b, table, bits, k_reversed);
}
#endif

struct pt2 sobol_point(struct sobol_seeds s, uint32_t k)
{
    return sobol_point_inline(s, k);
}

void sobol_fill(struct sobol_seeds s, size_t n, struct pt2 *out)
{
    for (size_t k = 0; k < n; k++)
        out[k] = sobol_point_inline(s, (uint32_t)k);
}
