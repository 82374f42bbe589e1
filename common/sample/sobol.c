/* sobol: the Owen-scrambled Sobol (0,2)-sequence, the sobol sampler's points.

   The construction follows Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)): the
   point of index i is the Sobol point of a shuffled index, each of its coordinates then Owen-
   scrambled, both by the hash Laine and Karras 2011 ("Stratified sampling for stochastic
   transparency", EGSR) use for a nested uniform scramble. Written here from the papers'
   descriptions; the hash's multipliers are the ones Burley lists. */
#include "sobol.h"

/* v's 32 bits in reverse order (digit 1 of a binary fraction becomes bit 0). */
static inline uint32_t bit_reverse(uint32_t v)
{
    v = (v >> 16) | (v << 16);
    v = ((v & 0xff00ff00u) >> 8) | ((v & 0x00ff00ffu) << 8);
    v = ((v & 0xf0f0f0f0u) >> 4) | ((v & 0x0f0f0f0fu) << 4);
    v = ((v & 0xccccccccu) >> 2) | ((v & 0x33333333u) << 2);
    return ((v & 0xaaaaaaaau) >> 1) | ((v & 0x55555555u) << 1);
}

/* Two reversals in one: v's 64 bits in reverse order, so (a << 32 | b) becomes rev(b) << 32 |
   rev(a) (a point's x and y: one byte swap and three mask steps for both, not two of each). */
static inline uint64_t bit_reverse_pair(uint64_t v)
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
static inline uint32_t owen_reversed(uint32_t r, uint32_t seed)
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

uint32_t sobol_x(uint32_t i)
{
    return bit_reverse(i);
}

uint32_t sobol_y(uint32_t i)
{
    return bit_reverse(sobol_y_reversed(i));
}

uint32_t sobol_owen(uint32_t v, uint32_t seed)
{
    return bit_reverse(owen_reversed(bit_reverse(v), seed));
}

struct sobol_seeds sobol_seeds_draw(struct rng *rng)
{
    struct sobol_seeds s;
    s.index = rng_u32(rng);
    s.x = rng_u32(rng);
    s.y = rng_u32(rng);
    return s;
}

/* The point whose reversed, unscrambled coordinates are xr and yr, each Owen-scrambled with its
   seed: both coordinates are bit reversals of a reversed value, so each costs one reversal,
   both done as one 64-bit. */
static inline struct pt2 scrambled_pair(uint32_t xr, uint32_t yr, uint32_t seed_x, uint32_t seed_y)
{
    const uint64_t yx = bit_reverse_pair((uint64_t)owen_reversed(xr, seed_x) << 32 | owen_reversed(yr, seed_y));
    const uint32_t x = (uint32_t)yx, y = (uint32_t)(yx >> 32);
    return (struct pt2){x * 0x1.0p-32, y * 0x1.0p-32};
}

/* Point k: index i = owen(k) (Burley's shuffle: the first 2^m shuffled indices are one aligned
   block of 2^m Sobol indices, itself a (0,m,2)-net), then x = owen(sobol_x(i)) and y =
   owen(sobol_y(i)), each with its own seed; Owen scrambling keeps a net a net. */
static inline struct pt2 point_of(struct sobol_seeds s, uint32_t k)
{
    const uint32_t i = sobol_owen(k, s.index);
    return scrambled_pair(i, sobol_y_reversed(i), s.x, s.y);
}

/* Sobol's first coordinate takes an index's low 32 bits only (32 digits); its second's generator
   matrix is Pascal's triangle mod 2, and a column k >= 32 equals column k - 32 in the first 32
   digits (Lucas's theorem), so the high half adds its own sobol_y. */
struct pt2 sobol_point64(uint64_t index, uint32_t seed_x, uint32_t seed_y)
{
    const uint32_t lo = (uint32_t)index, hi = (uint32_t)(index >> 32);
    return scrambled_pair(lo, sobol_y_reversed(lo) ^ sobol_y_reversed(hi), seed_x, seed_y);
}

struct pt2 sobol_point(struct sobol_seeds s, uint32_t k)
{
    return point_of(s, k);
}

void sobol_fill(struct sobol_seeds s, size_t n, struct pt2 *out)
{
    for (size_t k = 0; k < n; k++)
        out[k] = point_of(s, (uint32_t)k);
}
