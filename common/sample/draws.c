/* draws: a Fisher-Yates shuffle's draws, several at a time (draws.h). */
#include "draws.h"

#include "base/simd.h"

#if SIMD_AVX2
#include <immintrin.h>
#endif

/* PCG's jump of four steps: s -> s a^4 + inc (a^3 + a^2 + a + 1) (rng.h's rng_uniform_pair). */
#define DRAWS_MULT4 0xfb4d3ae39272be11ULL
#define DRAWS_INC4 0xcbb5f646404a560cULL

#if SIMD_AVX2
/* Draws k = 0 .. count - 1 (count a multiple of 4) of the stream at state s, increment inc, below
   bound - k: four lanes of states k .. k + 3, each step a jump of four (the 64-bit multiply from
   three 32-bit ones), PCG's output (XSH RR: its rotation by a variable shift on each lane) and
   Lemire's multiply. Returns the state after them. */
__attribute__((target("avx2"))) static uint64_t draws_avx2(uint64_t s, uint64_t inc, size_t count,
                                                           uint32_t bound, uint32_t *out)
{
    const uint64_t s1 = s * RNG_MULT + inc, s2 = s1 * RNG_MULT + inc, s3 = s2 * RNG_MULT + inc;
    __m256i st = _mm256_set_epi64x((long long)s3, (long long)s2, (long long)s1, (long long)s);
    const __m256i a_lo = _mm256_set1_epi64x((long long)(DRAWS_MULT4 & 0xffffffffu)),
                  a_hi = _mm256_set1_epi64x((long long)(DRAWS_MULT4 >> 32)),
                  c4 = _mm256_set1_epi64x((long long)(inc * DRAWS_INC4)),
                  low32 = _mm256_set1_epi64x(0xffffffff), thirty_two = _mm256_set1_epi64x(32),
                  four = _mm256_set1_epi64x(4);
    __m256i below =
        _mm256_set_epi64x((long long)bound - 3, (long long)bound - 2, (long long)bound - 1, (long long)bound);
    for (size_t k = 0; k < count; k += 4) {
        const __m256i x = _mm256_and_si256(
                          _mm256_srli_epi64(_mm256_xor_si256(_mm256_srli_epi64(st, 18), st), 27), low32),
                      rot = _mm256_srli_epi64(st, 59);
        const __m256i turned = _mm256_or_si256(_mm256_srlv_epi64(x, rot),
                                               _mm256_sllv_epi64(x, _mm256_sub_epi64(thirty_two, rot)));
        const __m256i j = _mm256_srli_epi64(_mm256_mul_epu32(turned, below), 32);
        /* the four 32-bit draws, in order, from the lanes' low halves */
        const __m256i packed = _mm256_permutevar8x32_epi32(j, _mm256_set_epi32(7, 5, 3, 1, 6, 4, 2, 0));
        _mm_storeu_si128((__m128i *)(void *)(out + k), _mm256_castsi256_si128(packed));
        const __m256i cross =
            _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(st, 32), a_lo), _mm256_mul_epu32(st, a_hi));
        st = _mm256_add_epi64(_mm256_add_epi64(_mm256_mul_epu32(st, a_lo), _mm256_slli_epi64(cross, 32)), c4);
        below = _mm256_sub_epi64(below, four);
    }
    return (uint64_t)_mm_cvtsi128_si64(_mm256_castsi256_si128(st));
}
#endif

void draws_below(struct rng *r, size_t count, uint32_t bound, uint32_t *out, int wide)
{
    size_t k = 0;
#if SIMD_AVX2
    if (wide && count >= 4) {
        k = count & ~(size_t)3;
        r->state = draws_avx2(r->state, r->inc, k, bound, out);
    }
#endif
    for (; k < count; k++)
        out[k] = rng_below(r, bound - (uint32_t)k);
}
