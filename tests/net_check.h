/* net_check: whether a 2D point set is a (0,m,2)-net in base 2 (test_sobol, test_pmj02, test_zsobol). */
#ifndef NET_CHECK_H
#define NET_CHECK_H

#include <stdlib.h>
#include <string.h>

#include "sample/pt2.h"

/* Whether the n points form a (0,m,2)-net in base 2, n = 2^m: every elementary interval
   [i / 2^a, (i + 1) / 2^a) x [j / 2^b, (j + 1) / 2^b) with a + b = m holds exactly one point.
   1 yes, 0 no (or n not a power of two), -1 out of memory. */
static inline int points_are_net(const struct pt2 *p, size_t n)
{
    int m = 0;
    while (((size_t)1 << m) < n)
        m++;
    if (n == 0 || n != (size_t)1 << m)
        return 0;
    unsigned char *count = calloc(n, 1);
    if (!count)
        return -1;
    int ok = 1;
    for (int a = 0; ok && a <= m; a++) {
        const int b = m - a;
        memset(count, 0, n);
        for (size_t k = 0; k < n; k++) {
            const size_t i = (size_t)(p[k].x * (double)((size_t)1 << a)),
                         j = (size_t)(p[k].y * (double)((size_t)1 << b));
            if (i >> a || j >> b || count[(i << b) | j]++)
                ok = 0;
        }
    }
    free(count);
    return ok;
}

#endif
