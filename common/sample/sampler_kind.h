/* sampler_kind: one row of traits per sampler kind (its name, set size at a threshold, expected
   samples per pixel, smallest threshold, walk, flags) that every other file reads. */
#ifndef SAMPLER_KIND_H
#define SAMPLER_KIND_H

#include <stddef.h>

enum sampler_kind {
    SAMPLER_UNIFORM,
    SAMPLER_JITTER,
    SAMPLER_RANDOM,
    SAMPLER_POISSON,
    SAMPLER_SOBOL,
    SAMPLER_HALTON,
    SAMPLER_PMJ02BN,
    SAMPLER_ZSOBOL
};

/* Largest set a job may ask for, per pixel or per light draw. */
#define SAMPLER_MAX_POINTS 4000000

/* How a set is taken point by point (sample/stream.h): drawn whole and its points shuffled
   (any sampler; a fresh Poisson set), or a cheaper walk a kind knows: its cells shuffled and a
   cell's point made when taken (uniform, jitter), independent points (random), a pool set's
   indices shuffled and a point shifted when taken (pooled Poisson), a set's indices shuffled and
   point k made when taken (sobol). */
enum sampler_walk {
    SAMPLER_WALK_WHOLE,
    SAMPLER_WALK_CELLS,
    SAMPLER_WALK_FREE,
    SAMPLER_WALK_POOL,
    SAMPLER_WALK_SOBOL
};

/* How a kind's set size follows from its threshold t (n = floor(100 / t)). */
enum sampler_count {
    SAMPLER_COUNT_SQUARE,  /* n x n points */
    SAMPLER_COUNT_POW2,    /* n x n rounded up to a power of two (nets at powers of two) */
    SAMPLER_COUNT_BRIDSON, /* at most one point per cell of Bridson's grid, ceil(sqrt(2) 100 / t)
                              on a side; about SAMPLER_POISSON_T2 / t^2 points expected */
};

/* A toroidal Poisson set's expected size: about SAMPLER_POISSON_T2 / t^2 points at threshold t
   (0.615 / r^2 for r = t / 100; docs/samplers.md measures it from 15 to 6145 points). */
#define SAMPLER_POISSON_T2 6150.0

/* What a kind is, for the sentences and checks that depend on it (not on its name). */
enum sampler_flag {
    SAMPLER_ALIASES = 1 << 0,  /* a regular grid: its structured error is aliasing */
    SAMPLER_BASELINE = 1 << 1, /* the stratified baseline a costly kind's price is told against */
    SAMPLER_POOLED = 1 << 2,   /* may draw from a pool of sets (poisson_pool), else fresh costly sets */
    SAMPLER_AT = 1 << 3,       /* points are an image-wide sequence's, placed by (seed, pixel, dim) */
};

struct sampler_traits {
    const char *name;
    enum sampler_count count;
    enum sampler_walk walk; /* a pool's sets walk SAMPLER_WALK_POOL whatever the row says */
    unsigned flags;         /* enum sampler_flag */
};

/* The row of kind (NULL for a value outside the enum). */
const struct sampler_traits *sampler_traits(enum sampler_kind kind);

/* Name <-> kind. parse returns 0, or -1 for an unknown name. */
int sampler_kind_parse(const char *name, enum sampler_kind *out);
const char *sampler_kind_name(enum sampler_kind kind);
/* Every kind's name in enum order, then NULL (for "did you mean" and usage lines). */
const char *const *sampler_kind_names(void);
/* The names joined by sep ("uniform | jitter | ..."), into buf of n bytes; returns buf. */
char *sampler_kind_list(const char *sep, char *buf, size_t n);
/* Whether kind's row carries flag. */
int sampler_kind_has(enum sampler_kind kind, enum sampler_flag flag);

/* 1 for a threshold in (0, 100], the range every kind takes. */
int sampler_threshold_valid(double threshold);

/* n = floor(100 / threshold): the grid side of uniform/jitter/random; sobol and halton draw n * n
   points, pmj02bn and zsobol n * n rounded up to a power of two. */
int sampler_grid_side(double threshold);

/* Upper bound on the size of one set of (kind, threshold): n*n for the grid kinds, sobol and halton,
   the background-grid cell count for poisson, the power of two at or above n*n for pmj02bn and
   zsobol. Fits in size_t for any threshold in (0, 100]. */
size_t sampler_capacity(enum sampler_kind kind, double threshold);

/* Bridson's background-grid side at threshold t: ceil(sqrt(2) 100 / t), nudged up so that rounding
   can never let two points at least t / 100 apart share a cell. */
double sampler_poisson_side(double threshold);

/* What a set holds on average: the capacity, or Poisson's expected count. */
double sampler_expected_spp(enum sampler_kind kind, double threshold);

/* The smallest threshold (to 4 digits, rounded up) whose sets fit SAMPLER_MAX_POINTS. */
double sampler_smallest_threshold(enum sampler_kind kind);

/* What a kind's capacity counts ("points", or "Bridson grid cells") and how its size follows
   from n ("n x n points", "n x n points rounded up to a power of two"). */
const char *sampler_capacity_unit(enum sampler_kind kind);
const char *sampler_count_rule(enum sampler_kind kind);

#endif
