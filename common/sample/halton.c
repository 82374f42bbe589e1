/* halton: Halton points with per-digit random permutations from tables cached per dimension, and
   pbrt-v4's per-pixel indexing (halton.h). */
#include "halton.h"

#include <stdlib.h>

#include "sobol.h"

static const uint32_t primes[2 * HALTON_DIMS] = {
    2,   3,   5,   7,   11,  13,  17,  19,  23,  29,  31,  37,  41,  43,  47,  53,
    59,  61,  67,  71,  73,  79,  83,  89,  97,  101, 103, 107, 109, 113, 127, 131,
    137, 139, 149, 151, 157, 163, 167, 173, 179, 181, 191, 193, 197, 199, 211, 223,
    227, 229, 233, 239, 241, 251, 257, 263, 269, 271, 277, 281, 283, 293, 307, 311};

/* The largest permutation a table holds (base 311), for the builder's scratch. */
#define MAX_BASE 311u

/* One dimension's tables: its key and the scrambles of its two bases (dimension 0: base 3 only). */
struct halton_slot {
    uint64_t seed;
    uint32_t dim;
    int full;
    struct halton_digits d[2];
};

/* Digits of base b a radical inverse keeps: the fewest with b^digits >= 2^32. */
static int digits_of(uint32_t b, double *scale)
{
    uint64_t s = 1;
    int n = 0;
    for (; s < ((uint64_t)1 << 32); n++)
        s *= b;
    *scale = (double)s;
    return n;
}

/* Words base b's tables take: digits * b images and digits + 1 tails. */
static size_t words_of(uint32_t b)
{
    double scale;
    const int n = digits_of(b, &scale);
    return (size_t)n * b + (size_t)n + 1;
}

/* Build base b's scramble for key into mem (words_of(b) words): digit position j's permutation is a
   Fisher-Yates shuffle of [0, b) from an rng stream of (key, j), so every digit's image is uniform
   and distinct digits' images distinct (Owen's per-digit property without the nesting). */
static struct halton_digits build(uint32_t b, uint64_t key, uint64_t *mem)
{
    struct halton_digits d;
    d.base = b;
    d.digits = digits_of(b, &d.scale);
    d.span = (uint64_t)d.scale;
    uint64_t *pw = mem, *tail = mem + (size_t)d.digits * b;
    uint64_t weight = (uint64_t)d.scale / b; /* b^(digits - 1 - j) */
    uint32_t perm[MAX_BASE];
    for (int j = 0; j < d.digits; j++, weight /= b) {
        struct rng r;
        rng_seed(&r, key, (uint64_t)j);
        for (uint32_t t = 0; t < b; t++)
            perm[t] = t;
        for (uint32_t t = 0; t + 1 < b; t++) {
            const uint32_t u = t + rng_below(&r, b - t), v = perm[u];
            perm[u] = perm[t];
            perm[t] = v;
        }
        for (uint32_t t = 0; t < b; t++)
            pw[(size_t)j * b + t] = perm[t] * weight;
    }
    tail[d.digits] = 0;
    for (int j = d.digits - 1; j >= 0; j--)
        tail[j] = tail[j + 1] + pw[(size_t)j * b];
    d.pw = pw;
    d.tail = tail;
    return d;
}

int halton_cache_init(struct halton_cache *c)
{
    *c = (struct halton_cache){0};
    c->words = words_of(3);
    for (uint32_t p = 1; p < HALTON_DIMS; p++) {
        const size_t w = words_of(primes[2 * p]) + words_of(primes[2 * p + 1]);
        c->words = w > c->words ? w : c->words;
    }
    c->mem = calloc((size_t)HALTON_CACHE_SLOTS * c->words, sizeof *c->mem);
    c->slots = calloc(HALTON_CACHE_SLOTS, sizeof *c->slots);
    if (!c->mem || !c->slots) {
        halton_cache_release(c);
        return -1;
    }
    return 0;
}

void halton_cache_release(struct halton_cache *c)
{
    free(c->mem);
    free(c->slots);
    *c = (struct halton_cache){0};
}

/* The scramble keys of (seed, dim): the first coordinate's, the second's is its mix. */
static uint64_t dim_key(uint64_t seed, uint32_t dim)
{
    return rng_mix64(seed ^ rng_mix64((uint64_t)dim + 0x4a170aULL));
}

/* The slot holding (seed, dim)'s tables, built on first use (open addressing; a cache three
   quarters full starts over: the tables are functions of their key, so the bits never depend on
   what it held). */
static const struct halton_slot *slot_of(struct halton_cache *c, uint64_t seed, uint32_t dim)
{
    uint32_t at = (uint32_t)rng_mix64(seed ^ ((uint64_t)dim << 20 | dim)) & (HALTON_CACHE_SLOTS - 1);
    for (;; at = (at + 1) & (HALTON_CACHE_SLOTS - 1)) {
        struct halton_slot *s = &c->slots[at];
        if (!s->full)
            break;
        if (s->seed == seed && s->dim == dim)
            return s;
    }
    if (c->used >= HALTON_CACHE_SLOTS * 3 / 4) {
        for (int i = 0; i < HALTON_CACHE_SLOTS; i++)
            c->slots[i].full = 0;
        c->used = 0;
        at = (uint32_t)rng_mix64(seed ^ ((uint64_t)dim << 20 | dim)) & (HALTON_CACHE_SLOTS - 1);
    }
    struct halton_slot *s = &c->slots[at];
    uint64_t *mem = c->mem + (size_t)at * c->words;
    const uint64_t h = dim_key(seed, dim);
    *s = (struct halton_slot){.seed = seed, .dim = dim, .full = 1};
    if (dim == 0) {
        s->d[0] = build(3, rng_mix64(h), mem);
    } else {
        const uint32_t pair = 1 + (dim - 1) % (HALTON_DIMS - 1);
        s->d[0] = build(primes[2 * pair], h, mem);
        s->d[1] = build(primes[2 * pair + 1], rng_mix64(h), mem + words_of(primes[2 * pair]));
    }
    c->used++;
    return s;
}

/* Base 2 under Owen's nested scramble: its first 32 binary digits are the low 32 index bits
   reversed, sobol.c's hash scrambles them (a hash per point, no table). */
static double owen2(uint64_t index, uint64_t key)
{
    return sobol_owen(sobol_x((uint32_t)index), (uint32_t)rng_mix64(key)) * 0x1.0p-32;
}

double halton_radical_inverse(uint32_t base, uint64_t index, uint64_t seed)
{
    if (base == 2)
        return owen2(index, seed);
    uint64_t mem[4 * MAX_BASE + 5] = {0};
    const struct halton_digits d = build(base, seed, mem);
    return halton_inverse(&d, index);
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

/* Sample i of the pixel whose first index is offset, under slot s's tables. Dimension 0 drops the
   digits that chose the pixel: (offset + i * 2^7 3^5) / 2^7 = offset / 2^7 + i * 3^5, and so for 3^5. */
static inline struct pt2 point_in(const struct halton_slot *s, uint64_t key, uint64_t offset, uint32_t i)
{
    if (s->dim == 0)
        return (struct pt2){owen2(offset / HALTON_TILE_X + (uint64_t)i * HALTON_TILE_Y, key),
                            halton_inverse(&s->d[0], offset / HALTON_TILE_Y + (uint64_t)i * HALTON_TILE_X)};
    /* never pair 0 again: its first digits are the pixel's, the same for all its samples */
    const uint64_t index = offset + (uint64_t)i * HALTON_STRIDE;
    return (struct pt2){halton_inverse(&s->d[0], index), halton_inverse(&s->d[1], index)};
}

void halton_fill(struct halton_cache *c, struct halton_key k, uint32_t n, struct pt2 *out)
{
    const struct halton_slot *s = slot_of(c, k.seed, k.dim);
    const uint64_t key = dim_key(k.seed, k.dim), offset = halton_pixel_offset(k.x, k.y);
    for (uint32_t i = 0; i < n; i++)
        out[i] = point_in(s, key, offset, i);
}
