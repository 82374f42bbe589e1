/* poisson_filter: the fixed point window filter of Bridson's sampler (poisson.c): is some
   sample in the 4 x 4 or 5 x 5 cells around a candidate closer than the limit? Internal to
   poisson.c; static inline so its loop keeps the window in registers. */
#ifndef POISSON_FILTER_H
#define POISSON_FILTER_H

#include <stddef.h>
#include <stdint.h>

/* Offsets within a cell in fixed point: units per cell width (int16 holds +-8 cells). */
#define POISSON_FIXED 4096

#if defined(__SSE2__) && !defined(POISSON_PORTABLE)
#include <emmintrin.h>
#endif

#if defined(__SSE2__) && !defined(POISSON_PORTABLE)
/* Lanes where the sample of one of 4 cells in a row (offsets at uv) is closer than the limit
   to the candidate c, both as (u, v) pairs of int16: (du, dv) squared and summed by one
   multiply-add (pmaddwd). */
static inline __m128i poisson_row_near(__m128i c, const int16_t *uv, __m128i limit)
{
    const __m128i d = _mm_sub_epi16(c, _mm_loadu_si128((const __m128i *)(const void *)uv));
    return _mm_cmplt_epi32(_mm_madd_epi16(d, d), limit);
}
#endif

/* Is some sample of the 4 x 4 cells from uv (a row every stride cells) closer than sqrt(near2)
   to (cu, cv)? All in fixed point, POISSON_FIXED per cell width, (cu, cv) measured from the
   first cell's corner, with cu + 2^16 cv packed in one word. One row of 4 cells is one 16-byte
   load and five instructions, with no branch: an empty cell just lies far away. Sums stay
   below 2^31: |du|, |dv| < 7 cells. */
static inline int poisson_near4(const int16_t *uv, ptrdiff_t stride, uint32_t cuv, int32_t near2)
{
    const int f = POISSON_FIXED;
#if defined(__SSE2__) && !defined(POISSON_PORTABLE)
    const __m128i steps = _mm_setr_epi16(0, 0, (int16_t)f, 0, (int16_t)(2 * f), 0, (int16_t)(3 * f), 0);
    const __m128i down = _mm_setr_epi16(0, (int16_t)f, 0, (int16_t)f, 0, (int16_t)f, 0, (int16_t)f);
    const __m128i limit = _mm_set1_epi32(near2);
    const __m128i c0 = _mm_sub_epi16(_mm_set1_epi32((int32_t)cuv), steps);
    const __m128i c1 = _mm_sub_epi16(c0, down), c2 = _mm_sub_epi16(c1, down), c3 = _mm_sub_epi16(c2, down);
    const __m128i hit = _mm_or_si128(
        _mm_or_si128(poisson_row_near(c0, uv, limit), poisson_row_near(c1, uv + 2 * stride, limit)),
        _mm_or_si128(poisson_row_near(c2, uv + 4 * stride, limit),
                     poisson_row_near(c3, uv + 6 * stride, limit)));
    return _mm_movemask_epi8(hit) != 0;
#else
    const int32_t cu = (int16_t)(cuv & 0xffffu), cv = (int16_t)(cuv >> 16);
    int hit = 0;
    for (int j = 0; j < 4; j++, uv += 2 * stride)
        for (int i = 0; i < 4; i++) {
            int32_t du = cu - i * f - uv[2 * i], dv = cv - j * f - uv[2 * i + 1];
            hit |= du * du + dv * dv < near2;
        }
    return hit;
#endif
}

/* poisson_near4 for a 5 x 5 window (r of 1.5 cells or more: thresholds above about 8.6, where
   no whole number of cells per side keeps r under 1.5 cells): the four 4 x 4 windows in its
   corners. (cu, cv) >= r > 1 cell from the first corner, so moving that corner by one cell
   keeps both fields positive. */
static inline int poisson_near5(const int16_t *uv, ptrdiff_t stride, uint32_t cuv, int32_t near2)
{
#if defined(__SSE2__) && !defined(POISSON_PORTABLE)
    /* rows of cells 0-3, then of cells 1-4 (the candidate one cell to the left of their corner) */
    const int f = POISSON_FIXED;
    const __m128i steps = _mm_setr_epi16(0, 0, (int16_t)f, 0, (int16_t)(2 * f), 0, (int16_t)(3 * f), 0);
    const __m128i down4 = _mm_setr_epi16(0, (int16_t)f, 0, (int16_t)f, 0, (int16_t)f, 0, (int16_t)f);
    const __m128i right4 = _mm_setr_epi16((int16_t)f, 0, (int16_t)f, 0, (int16_t)f, 0, (int16_t)f, 0);
    const __m128i limit = _mm_set1_epi32(near2);
    __m128i c = _mm_sub_epi16(_mm_set1_epi32((int32_t)cuv), steps), hit = _mm_setzero_si128();
    for (int j = 0; j < 5; j++, c = _mm_sub_epi16(c, down4), uv += 2 * stride)
        hit = _mm_or_si128(hit, _mm_or_si128(poisson_row_near(c, uv, limit),
                                             poisson_row_near(_mm_sub_epi16(c, right4), uv + 2, limit)));
    return _mm_movemask_epi8(hit) != 0;
#else
    const uint32_t right = POISSON_FIXED, down = (uint32_t)POISSON_FIXED << 16;
    return poisson_near4(uv, stride, cuv, near2) | poisson_near4(uv + 2, stride, cuv - right, near2) |
           poisson_near4(uv + 2 * stride, stride, cuv - down, near2) |
           poisson_near4(uv + 2 * stride + 2, stride, cuv - right - down, near2);
#endif
}

/* The filter for a window of w cells (4 or 5). */
static inline int poisson_near(const int16_t *uv, ptrdiff_t stride, uint32_t cuv, int32_t near2, int w)
{
    return w == 4 ? poisson_near4(uv, stride, cuv, near2) : poisson_near5(uv, stride, cuv, near2);
}

#endif
