/* check: a tiny test harness; each test binary ends with "N passed, N failed". */
#ifndef CHECK_H
#define CHECK_H

#include <math.h>
#include <stdio.h>

static int check_passed, check_failed;

#define CHECK(expr)                                                                                          \
    do {                                                                                                     \
        if (expr)                                                                                            \
            check_passed++;                                                                                  \
        else {                                                                                               \
            check_failed++;                                                                                  \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #expr);                         \
        }                                                                                                    \
    } while (0)

#define CHECK_NEAR(a, b, eps)                                                                                \
    do {                                                                                                     \
        double check_a_ = (a), check_b_ = (b);                                                               \
        if (fabs(check_a_ - check_b_) <= (eps))                                                              \
            check_passed++;                                                                                  \
        else {                                                                                               \
            check_failed++;                                                                                  \
            fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s = %.9g, %s = %.9g, eps %g\n", __FILE__, __LINE__,  \
                    #a, check_a_, #b, check_b_, (double)(eps));                                              \
        }                                                                                                    \
    } while (0)

static inline int check_report(const char *name)
{
    printf("%s: %d passed, %d failed\n", name, check_passed, check_failed);
    return check_failed ? 1 : 0;
}

#endif
