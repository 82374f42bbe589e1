/* test_draws: a shuffle's draws made several at a time are rng_below's, one by one, value for
   value, and leave the stream where the one-by-one draws leave it. */
#include "sample/draws.h"

#include "base/simd.h"

#include "check.h"

/* Every count from 0 to 70 and a few larger, bounds from count to near 2^32, many streams: the
   wide path (when the processor has it) and the one-by-one path against rng_below. */
static void test_same_draws(void)
{
    static const uint32_t extra[] = {64, 100, 1156, 4096};
    static uint32_t out[5000];
    int same = 1, cases = 0;
    for (int wide = 0; wide <= simd_avx2(); wide++)
        for (uint32_t c = 0; c < 70 + 4; c++) {
            const uint32_t count = c < 70 ? c : extra[c - 70];
            for (uint64_t seed = 0; seed < 40; seed++) {
                const uint32_t bound =
                    seed % 4 == 3 ? 0xfffffff0u - (uint32_t)seed : count + (uint32_t)seed % 3;
                struct rng a, b;
                rng_pixel(&a, seed, (int)count, 3, 16 + seed);
                b = a;
                draws_below(&a, count, bound, out, wide);
                for (uint32_t k = 0; k < count; k++)
                    same &= out[k] == rng_below(&b, bound - k);
                same &= a.state == b.state && a.inc == b.inc;
                cases++;
            }
        }
    CHECK(same);
    CHECK(cases >= 74 * 40);
}

int main(void)
{
    test_same_draws();
    return check_report("test_draws");
}
