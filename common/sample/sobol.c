/* sobol: the Owen-scrambled Sobol (0,2)-sequence, the sobol sampler's points.

   The construction follows Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)): the
   point of index i is the Sobol point of a shuffled index, each of its coordinates then Owen-
   scrambled, both by the hash Laine and Karras 2011 ("Stratified sampling for stochastic
   transparency", EGSR) use for a nested uniform scramble. Written here from the papers'
   descriptions; the hash's multipliers are the ones Burley lists. */
#include "sobol.h"

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

struct pt2 sobol_point(struct sobol_seeds s, uint32_t k)
{
    return sobol_point_inline(s, k);
}

void sobol_fill(struct sobol_seeds s, size_t n, struct pt2 *out)
{
    for (size_t k = 0; k < n; k++)
        out[k] = sobol_point_inline(s, (uint32_t)k);
}
