/* rng: PCG32 (O'Neill 2014) streams, seeded per pixel so a pixel never depends on the row split. */
#ifndef RNG_H
#define RNG_H

#include <stdint.h>

struct rng {
    uint64_t state, inc;
};

/* SplitMix64 finaliser (Steele et al. 2014): a good 64-bit mix for deriving seeds. */
static inline uint64_t rng_mix64(uint64_t z)
{
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

#define RNG_MULT 6364136223846793005ULL

/* PCG32's output for a state (XSH RR). */
static inline uint32_t rng_output(uint64_t state)
{
    uint32_t xorshifted = (uint32_t)(((state >> 18u) ^ state) >> 27u);
    uint32_t rot = (uint32_t)(state >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
}

static inline uint32_t rng_u32(struct rng *r)
{
    uint64_t old = r->state;
    r->state = old * RNG_MULT + r->inc;
    return rng_output(old);
}

/* The value rng_u32 would return next, without advancing r. */
static inline uint32_t rng_peek_u32(const struct rng *r)
{
    return rng_output(r->state);
}

/* Seed a stream: distinct `stream` values give independent sequences for the same seed. */
static inline void rng_seed(struct rng *r, uint64_t seed, uint64_t stream)
{
    r->state = 0u;
    r->inc = (stream << 1u) | 1u;
    rng_u32(r);
    r->state += seed;
    rng_u32(r);
}

/* Uniform double in [0, 1) with 53 random bits. */
static inline double rng_uniform(struct rng *r)
{
    uint64_t hi = rng_u32(r), lo = rng_u32(r);
    return (double)(((hi << 32) | lo) >> 11) * 0x1.0p-53;
}

/* u = rng_uniform(r), v = rng_uniform(r): the same values and final state, but the four states
   made from the first at once by PCG's jump-ahead (k steps: s a^k + inc (a^(k-1) + ... + 1),
   mod 2^64), a chain of one multiply-add instead of four (a jittered set's points wait on it). */
static inline void rng_uniform_pair(struct rng *r, double *u, double *v)
{
    const uint64_t s0 = r->state, c = r->inc;
    const uint64_t s1 = s0 * RNG_MULT + c, s2 = s0 * 0x685f98a2018fade9ULL + c * 0x5851f42d4c957f2eULL,
                   s3 = s0 * 0x0b046976f22528f5ULL + c * 0xc0b18ccf4e252d17ULL;
    r->state = s0 * 0xfb4d3ae39272be11ULL + c * 0xcbb5f646404a560cULL;
    *u = (double)((((uint64_t)rng_output(s0) << 32) | rng_output(s1)) >> 11) * 0x1.0p-53;
    *v = (double)((((uint64_t)rng_output(s2) << 32) | rng_output(s3)) >> 11) * 0x1.0p-53;
}

/* Uniform double in [0, 1) with 32 random bits: one PCG step instead of two, where a
   direction or a coin needs no more resolution than 2^-32. */
static inline double rng_uniform32(struct rng *r)
{
    return rng_u32(r) * 0x1.0p-32;
}

/* Uniform integer in [0, n), n > 0 (Lemire's multiply; bias below 2^-32 * n). */
static inline uint32_t rng_below(struct rng *r, uint32_t n)
{
    return (uint32_t)(((uint64_t)rng_u32(r) * n) >> 32);
}

/* The stream for one pixel of one job: depends on (seed, x, y) only. */
static inline void rng_pixel(struct rng *r, uint64_t seed, int x, int y, uint64_t purpose)
{
    uint64_t key = rng_mix64(seed ^ rng_mix64(((uint64_t)(uint32_t)x << 32) | (uint32_t)y) ^
                             (purpose * 0xd1b54a32d192ed03ULL));
    rng_seed(r, key, rng_mix64(key + 1));
}

#endif
