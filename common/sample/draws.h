/* draws: a Fisher-Yates shuffle's draws of PCG32 (rng_below's), made several at a time: every
   draw is a function of the stream's state alone (PCG jumps ahead), so a block of them is
   computed side by side with AVX2 where the processor has it, the same values as one by one. */
#ifndef DRAWS_H
#define DRAWS_H

#include <stddef.h>
#include <stdint.h>

#include "base/rng.h"

/* out[k] = rng_below(r, bound - k) for k = 0 .. count - 1, drawn in that order from r, which is
   left as those draws leave it (count <= bound, bound <= 2^32 - 1). wide: simd_avx2()'s answer (0
   always gives the one-by-one path). Cannot fail. */
void draws_below(struct rng *r, size_t count, uint32_t bound, uint32_t *out, int wide);

#endif
