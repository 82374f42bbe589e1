/* halton: Owen-scrambled Halton points with pbrt-v4's per-pixel indexing (halton.h). */
#include "halton.h"

#include "sobol.h"

static const uint32_t primes[2 * HALTON_DIMS] = {
    2,   3,   5,   7,   11,  13,  17,  19,  23,  29,  31,  37,  41,  43,  47,  53,
    59,  61,  67,  71,  73,  79,  83,  89,  97,  101, 103, 107, 109, 113, 127, 131,
    137, 139, 149, 151, 157, 163, 167, 173, 179, 181, 191, 193, 197, 199, 211, 223,
    227, 229, 233, 239, 241, 251, 257, 263, 269, 271, 277, 281, 283, 293, 307, 311};

/* digit's image under the node's permutation of [0, b) keyed by h: d -> a d + r mod b with a in
   [1, b) and r in [0, b) from h (b prime: a bijection). Any one digit's image is uniform, and any
   two digits' images a uniform pair of distinct digits, the two properties Owen's variance results
   use (random linear scrambling, Matousek 1998, "On the L2-discrepancy for anchored boxes", J.
   Complexity 14). */
static uint32_t permute_digit(uint32_t digit, uint32_t b, uint64_t h)
{
    const uint64_t a = 1 + (uint32_t)h % (b - 1 ? b - 1 : 1), r = (h >> 32) % b;
    return (uint32_t)((a * digit + r) % b);
}

double halton_radical_inverse(uint32_t base, uint64_t index, uint64_t seed)
{
    if (base == 2) /* the first 32 binary digits are the low 32 index bits reversed: sobol.c's
                      Owen scramble of them is the nested uniform one, a hash per point */
        return sobol_owen(sobol_x((uint32_t)index), (uint32_t)rng_mix64(seed)) * 0x1.0p-32;
    /* digits until base^count >= 2^32; the value is numerator / base^count, one correctly rounded
       division of two exact integers (base^count < 2^41), the same bits everywhere */
    uint64_t numerator = 0, scale = 1, prefix = rng_mix64(seed ^ base);
    while (scale < ((uint64_t)1 << 32)) {
        const uint32_t digit = (uint32_t)(index % base);
        index /= base;
        numerator = numerator * base + permute_digit(digit, base, prefix);
        scale *= base;
        prefix = rng_mix64(prefix + digit + 1);
    }
    double v = (double)numerator / (double)scale;
    return v < 1.0 ? v : 0x1.fffffffffffffp-1;
}

/* v's low `digits` digits in base b, reversed. */
static uint32_t reverse_digits(uint32_t v, uint32_t b, int digits)
{
    uint32_t r = 0;
    for (int k = 0; k < digits; k++, v /= b)
        r = r * b + v % b;
    return r;
}

uint64_t halton_pixel_offset(uint32_t x, uint32_t y)
{
    /* index = a mod 128 and = c mod 243: a * 243 * (243^-1 mod 128) + c * 128 * (128^-1 mod 243),
       with 243^-1 = 59 (mod 128) and 128^-1 = 131 (mod 243) */
    const uint64_t a = reverse_digits(x % HALTON_TILE_X, 2, 7), c = reverse_digits(y % HALTON_TILE_Y, 3, 5);
    return (a * HALTON_TILE_Y * 59u + c * HALTON_TILE_X * 131u) % HALTON_STRIDE;
}

struct pt2 halton_point(struct halton_key k, uint32_t i)
{
    const uint64_t index = halton_pixel_offset(k.x, k.y) + (uint64_t)i * HALTON_STRIDE;
    const uint64_t h = rng_mix64(k.seed ^ rng_mix64((uint64_t)k.dim + 0x4a170aULL));
    if (k.dim == 0)
        return (struct pt2){halton_radical_inverse(2, index / HALTON_TILE_X, h),
                            halton_radical_inverse(3, index / HALTON_TILE_Y, rng_mix64(h))};
    /* never pair 0 again: its first digits are the pixel's, the same for all its samples */
    const uint32_t pair = 1 + (k.dim - 1) % (HALTON_DIMS - 1);
    return (struct pt2){halton_radical_inverse(primes[2 * pair], index, h),
                        halton_radical_inverse(primes[2 * pair + 1], index, rng_mix64(h))};
}

void halton_fill(struct halton_key k, uint32_t n, struct pt2 *out)
{
    for (uint32_t i = 0; i < n; i++)
        out[i] = halton_point(k, i);
}
