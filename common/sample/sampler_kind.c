/* sampler_kind: one row of traits per sampler kind that every other file reads. */
#include "sampler_kind.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define SAMPLER_SQRT2 1.41421356237309504880

/* The samplers, in enum sampler_kind's order: name, how its set size follows from a threshold,
   how its sets are walked, flags. A new sampler is a row here, an enum value and its draw
   function (sampler.c's table; docs/architecture.md, "How to add a sampler"). */
#define SAMPLER_ROWS(X)                                                                                      \
    X("uniform", SAMPLER_COUNT_SQUARE, SAMPLER_WALK_CELLS, SAMPLER_ALIASES)                                  \
    X("jitter", SAMPLER_COUNT_SQUARE, SAMPLER_WALK_CELLS, SAMPLER_BASELINE)                                  \
    X("random", SAMPLER_COUNT_SQUARE, SAMPLER_WALK_FREE, 0)                                                  \
    X("poisson", SAMPLER_COUNT_BRIDSON, SAMPLER_WALK_WHOLE, SAMPLER_POOLED)                                  \
    X("sobol", SAMPLER_COUNT_SQUARE, SAMPLER_WALK_SOBOL, 0)                                                  \
    X("halton", SAMPLER_COUNT_SQUARE, SAMPLER_WALK_WHOLE, SAMPLER_AT)                                        \
    X("pmj02bn", SAMPLER_COUNT_POW2, SAMPLER_WALK_WHOLE, 0)                                                  \
    X("zsobol", SAMPLER_COUNT_POW2, SAMPLER_WALK_WHOLE, SAMPLER_AT)
#define AS_ROW(name, count, walk, flags) {name, count, walk, flags},
#define AS_NAME(name, count, walk, flags) name,
static const struct sampler_traits rows[] = {SAMPLER_ROWS(AS_ROW)};
static const char *const names[] = {SAMPLER_ROWS(AS_NAME) NULL};
#define KIND_COUNT ((int)(sizeof rows / sizeof rows[0]))
_Static_assert(KIND_COUNT == SAMPLER_ZSOBOL + 1, "a row per kind");

const struct sampler_traits *sampler_traits(enum sampler_kind kind)
{
    return (int)kind < 0 || (int)kind >= KIND_COUNT ? NULL : &rows[kind];
}

int sampler_kind_parse(const char *name, enum sampler_kind *out)
{
    for (int i = 0; i < KIND_COUNT; i++) {
        if (name && strcmp(name, rows[i].name) == 0) {
            *out = (enum sampler_kind)i;
            return 0;
        }
    }
    return -1;
}

const char *sampler_kind_name(enum sampler_kind kind)
{
    const struct sampler_traits *r = sampler_traits(kind);
    return r ? r->name : "unknown";
}

const char *const *sampler_kind_names(void)
{
    return names;
}

char *sampler_kind_list(const char *sep, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < KIND_COUNT && used < n; i++) {
        int w = snprintf(buf + used, n - used, "%s%s", i ? sep : "", rows[i].name);
        used += w > 0 ? (size_t)w : 0;
    }
    return buf;
}

int sampler_kind_has(enum sampler_kind kind, enum sampler_flag flag)
{
    const struct sampler_traits *r = sampler_traits(kind);
    return r && (r->flags & (unsigned)flag) != 0;
}

int sampler_threshold_valid(double threshold)
{
    return threshold > 0.0 && threshold <= 100.0;
}

/* floor(100 / threshold), read as a person would: a threshold within a relative 1e-9 of 100 / m
   gives m (6.250000001 gives 16, and 0.1 gives 1000 although 100 / 0.1 is 999.9999999999999 in
   doubles). The one place a threshold becomes a grid side. */
static double grid_side_real(double threshold)
{
    const double q = 100.0 / threshold, m = floor(q + 0.5);
    if (m >= 1.0 && fabs(threshold - 100.0 / m) <= 1e-9 * (100.0 / m))
        return m;
    return floor(q);
}

double sampler_poisson_side(double threshold)
{
    return ceil(SAMPLER_SQRT2 * 100.0 / threshold * (1.0 + 1e-12));
}

int sampler_grid_side(double threshold)
{
    if (!sampler_threshold_valid(threshold))
        return 0;
    double n = grid_side_real(threshold);
    return n >= (double)INT32_MAX ? INT32_MAX : (int)n;
}

/* side * side, saturating at SIZE_MAX. */
static size_t side_squared(double side)
{
    if (side >= 4294967295.0 || side * side >= (double)SIZE_MAX)
        return SIZE_MAX;
    return (size_t)side * (size_t)side;
}

size_t sampler_capacity(enum sampler_kind kind, double threshold)
{
    const struct sampler_traits *r = sampler_traits(kind);
    if (!r || !sampler_threshold_valid(threshold))
        return 0;
    if (r->count == SAMPLER_COUNT_BRIDSON)
        return side_squared(sampler_poisson_side(threshold));
    size_t n = side_squared(grid_side_real(threshold));
    if (r->count != SAMPLER_COUNT_POW2)
        return n;
    size_t pow2 = 1;
    while (pow2 < n && pow2 <= SIZE_MAX / 2)
        pow2 *= 2;
    return pow2 < n ? SIZE_MAX : pow2;
}

double sampler_expected_spp(enum sampler_kind kind, double threshold)
{
    const struct sampler_traits *r = sampler_traits(kind);
    if (r && r->count == SAMPLER_COUNT_BRIDSON && sampler_threshold_valid(threshold))
        return SAMPLER_POISSON_T2 / (threshold * threshold);
    return (double)sampler_capacity(kind, threshold);
}

double sampler_smallest_threshold(enum sampler_kind kind)
{
    const struct sampler_traits *r = sampler_traits(kind);
    const enum sampler_count c = r ? r->count : SAMPLER_COUNT_SQUARE;
    /* pow2 kinds round n * n up to a power of two: n * n <= the largest power of two in the limit */
    double most = c == SAMPLER_COUNT_POW2 ? 2097152.0 : (double)SAMPLER_MAX_POINTS;
    double side = floor(sqrt(most));
    /* grid kinds: n = floor(100 / t) <= side; poisson: Bridson's grid side ceil(sqrt(2) 100 / t) <= side */
    double t = c == SAMPLER_COUNT_BRIDSON ? sqrt(2.0) * 100.0 / side : 100.0 / (side + 1.0);
    return ceil(t * (1.0 + 1e-9) * 1e4) / 1e4;
}

const char *sampler_capacity_unit(enum sampler_kind kind)
{
    const struct sampler_traits *r = sampler_traits(kind);
    return r && r->count == SAMPLER_COUNT_BRIDSON ? "Bridson grid cells" : "points";
}

const char *sampler_count_rule(enum sampler_kind kind)
{
    const struct sampler_traits *r = sampler_traits(kind);
    return r && r->count == SAMPLER_COUNT_POW2 ? "n x n points rounded up to a power of two" : "n x n points";
}
