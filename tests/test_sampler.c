/* test_sampler: set sizes, cells and disks, determinism, the pool's rotation, bad input, and the
   convergence rates of the four samplers on two integrands. */
#include "sample/sampler.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "base/vec3.h"

#define GAUSS_EXACT 0.5577462853510335         /* (integral of exp(-x^2) over [0, 1])^2 */
#define QUARTER_DISK_R2 0.63661977236758134308 /* 2 / pi: the disk covers half the square */

static const enum sampler_kind grid_kinds[] = {SAMPLER_UNIFORM, SAMPLER_JITTER, SAMPLER_RANDOM};

/* One set of (kind, threshold) drawn with rng (seed, 0); *out is malloc'd, the count returned. */
static size_t draw_set(enum sampler_kind kind, double threshold, uint64_t seed, struct pt2 **out)
{
    struct err e;
    struct sampler *s = sampler_new(kind, threshold, 0, 0, &e);
    *out = NULL;
    if (!s)
        return 0;
    *out = malloc(sampler_set_capacity(s) * sizeof **out);
    struct rng rng;
    rng_seed(&rng, seed, 0);
    size_t n = sampler_draw(s, &rng, *out);
    sampler_free(s);
    return n;
}

static int all_in_unit_square(const struct pt2 *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!(p[i].x >= 0.0 && p[i].x < 1.0 && p[i].y >= 0.0 && p[i].y < 1.0))
            return 0;
    return 1;
}

/* Squared distance, modulo 1 on each axis when torus is set. */
static double dist2(struct pt2 a, struct pt2 b, int torus)
{
    double dx = fabs(a.x - b.x), dy = fabs(a.y - b.y);
    if (torus) {
        dx = dx > 0.5 ? 1.0 - dx : dx;
        dy = dy > 0.5 ? 1.0 - dy : dy;
    }
    return dx * dx + dy * dy;
}

/* Smallest pairwise distance, brute force. */
static double min_distance(const struct pt2 *p, size_t n, int torus)
{
    double best = INFINITY;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++) {
            double d = dist2(p[i], p[j], torus);
            best = d < best ? d : best;
        }
    return sqrt(best);
}

/* Largest distance from a probe of a probes x probes grid of the unit square to its nearest
   sample, brute force. */
static double max_gap(const struct pt2 *p, size_t n, int probes, int torus)
{
    double worst = 0.0;
    for (int j = 0; j < probes; j++)
        for (int i = 0; i < probes; i++) {
            struct pt2 q = {(i + 0.5) / probes, (j + 0.5) / probes};
            double best = INFINITY;
            for (size_t k = 0; k < n; k++) {
                double d = dist2(q, p[k], torus);
                best = d < best ? d : best;
            }
            worst = best > worst ? best : worst;
        }
    return sqrt(worst);
}

static void test_names_and_sizes(void)
{
    const char *names[] = {"uniform", "jitter", "random", "poisson", "sobol", "halton", "pmj02bn", "zsobol"};
    for (int k = 0; k < 8; k++) {
        enum sampler_kind kind;
        CHECK(sampler_kind_parse(names[k], &kind) == 0 && (int)kind == k);
        CHECK(strcmp(sampler_kind_name(kind), names[k]) == 0);
        CHECK(strcmp(sampler_kind_names()[k], names[k]) == 0);
    }
    CHECK(sampler_kind_names()[8] == NULL);
    /* halton: n * n; pmj02bn and zsobol: n * n rounded up to a power of two */
    CHECK(sampler_capacity(SAMPLER_HALTON, 10) == 100 && sampler_capacity(SAMPLER_PMJ02BN, 10) == 128);
    CHECK(sampler_capacity(SAMPLER_ZSOBOL, 6.25) == 256 && sampler_capacity(SAMPLER_ZSOBOL, 100) == 1);
    enum sampler_kind kind = SAMPLER_RANDOM;
    CHECK(sampler_kind_parse("foo", &kind) == -1 && kind == SAMPLER_RANDOM);
    CHECK(sampler_kind_parse("Poisson", &kind) == -1);

    CHECK(sampler_grid_side(1) == 100);
    CHECK(sampler_grid_side(5) == 20);
    CHECK(sampler_grid_side(3) == 33);
    CHECK(sampler_grid_side(100) == 1);
    CHECK(sampler_grid_side(0.1) == 1000); /* 100 / 0.1 is 999.99... in doubles */
    CHECK(sampler_grid_side(100.0 / 128) == 128);
    /* within a relative 1e-9 of 100 / n: n, as a person reads it; farther: the floor */
    CHECK(sampler_grid_side(6.250000001) == 16 && sampler_grid_side(9.0909090919) == 11);
    CHECK(sampler_grid_side(6.2500001) == 15 && sampler_grid_side(9.09091) == 10);
    CHECK(sampler_capacity(SAMPLER_JITTER, 6.250000001) == 256);
    CHECK(sampler_grid_side(0) == 0 && sampler_grid_side(NAN) == 0);
    CHECK(sampler_capacity(SAMPLER_UNIFORM, 1) == 10000);
    CHECK(sampler_capacity(SAMPLER_JITTER, 0.1) == 1000000);
    CHECK(sampler_capacity(SAMPLER_POISSON, 1) == 142 * 142); /* ceil(sqrt(2) / 0.01) */
    CHECK(sampler_capacity(SAMPLER_POISSON, 100) == 4);
    CHECK(sampler_capacity(SAMPLER_RANDOM, 1e-300) == SIZE_MAX);
}

static void test_grid_counts(void)
{
    const double thresholds[] = {1, 5, 3, 100};
    const size_t counts[] = {10000, 400, 1089, 1};
    for (int k = 0; k < 3; k++)
        for (int t = 0; t < 4; t++) {
            struct pt2 *p;
            size_t n = draw_set(grid_kinds[k], thresholds[t], 1, &p);
            CHECK(n == counts[t]);
            CHECK(all_in_unit_square(p, n));
            free(p);
        }

    /* uniform: the cell centres of the whole square */
    struct pt2 *p;
    size_t n = draw_set(SAMPLER_UNIFORM, 3, 1, &p);
    int centred = n == 33 * 33;
    for (size_t k = 0; k < n && centred; k++) {
        double i = p[k].x * 33 - 0.5, j = p[k].y * 33 - 0.5;
        centred = fabs(i - floor(i + 0.5)) < 1e-9 && fabs(j - floor(j + 0.5)) < 1e-9;
    }
    CHECK(centred);
    free(p);

    /* jitter: exactly one point in each cell, for a few grid sides */
    const double jitter_thresholds[] = {3, 1, 0.7, 100.0 / 128};
    for (int t = 0; t < 4; t++) {
        int side = sampler_grid_side(jitter_thresholds[t]);
        n = draw_set(SAMPLER_JITTER, jitter_thresholds[t], 7, &p);
        int *hits = calloc((size_t)side * (size_t)side, sizeof *hits);
        int once = n == (size_t)side * (size_t)side && all_in_unit_square(p, n);
        for (size_t k = 0; k < n && once; k++)
            hits[(size_t)(p[k].y * side) * (size_t)side + (size_t)(p[k].x * side)]++;
        for (size_t c = 0; c < (size_t)side * (size_t)side && once; c++)
            once = hits[c] == 1;
        CHECK(once);
        free(hits);
        free(p);
    }
}

static void test_poisson_counts(void)
{
    int in_range = 1;
    for (uint64_t seed = 1; seed <= 20; seed++) {
        struct pt2 *p;
        size_t n = draw_set(SAMPLER_POISSON, 1, seed, &p);
        in_range &= n >= 6000 && n <= 6700 && all_in_unit_square(p, n);
        free(p);
    }
    CHECK(in_range);

    struct pt2 *p;
    size_t n = draw_set(SAMPLER_POISSON, 5, 3, &p);
    CHECK(n >= 230 && n <= 290);
    free(p);

    /* t = 100: r is the side of the square, yet two points in opposite corners are up to
       sqrt(2) apart, so Bridson keeps a second point now and then (about 8% of sets). */
    int ones = 0, twos = 0, apart = 1;
    for (uint64_t seed = 1; seed <= 200; seed++) {
        n = draw_set(SAMPLER_POISSON, 100, seed, &p);
        ones += n == 1;
        twos += n == 2;
        if (n == 2)
            apart &= dist2(p[0], p[1], 0) >= 1.0;
        free(p);
    }
    CHECK(ones + twos == 200);
    CHECK(ones > twos);
    CHECK(apart);
}

static void test_poisson_disks(void)
{
    /* no two points closer than r, and no probe farther than 2r from every point */
    for (uint64_t seed = 1; seed <= 4; seed++) {
        struct pt2 *p;
        size_t n = draw_set(SAMPLER_POISSON, 3, seed, &p);
        CHECK(all_in_unit_square(p, n));
        CHECK(min_distance(p, n, 0) >= 0.03 * (1 - 1e-12));
        CHECK(max_gap(p, n, 200, 1) < 2 * 0.03); /* toroidal: gaps wrap around */
        free(p);
    }
    /* a denser set, brute force still (19 million pairs) */
    struct pt2 *p;
    size_t n = draw_set(SAMPLER_POISSON, 1, 11, &p);
    CHECK(min_distance(p, n, 0) >= 0.01 * (1 - 1e-12));
    free(p);
    /* r > 0.086 needs more than 4 x 4 cells and skips the single-precision filter; plain and
       toroidal (a pool of one) */
    const double coarse[] = {10, 20, 45};
    for (int t = 0; t < 3; t++) {
        double r = coarse[t] / 100;
        struct err e;
        struct sampler *torus = sampler_new(SAMPLER_POISSON, coarse[t], 1, 3, &e);
        for (uint64_t seed = 1; seed <= 3; seed++) {
            n = draw_set(SAMPLER_POISSON, coarse[t], seed, &p);
            CHECK(all_in_unit_square(p, n));
            CHECK(min_distance(p, n, 0) >= r * (1 - 1e-12));
            CHECK(max_gap(p, n, 100, 1) < 2 * r);
            struct rng rng;
            rng_seed(&rng, seed, 0);
            n = sampler_draw(torus, &rng, p);
            CHECK(all_in_unit_square(p, n));
            CHECK(min_distance(p, n, 1) >= r * (1 - 1e-12));
            CHECK(max_gap(p, n, 100, 1) < 2 * r);
            free(p);
        }
        sampler_free(torus);
    }
}

/* Minimum distance of a large set through a bucket grid (cells of size r): the test's own
   independent neighbour search. */
static double min_distance_bucketed(const struct pt2 *p, size_t n, double r, int torus)
{
    int side = (int)(1.0 / r);
    int *head = malloc((size_t)side * (size_t)side * sizeof *head);
    int *next = malloc(n * sizeof *next);
    for (size_t c = 0; c < (size_t)side * (size_t)side; c++)
        head[c] = -1;
    for (size_t k = 0; k < n; k++) {
        int i = (int)(p[k].x * side), j = (int)(p[k].y * side);
        size_t c = (size_t)j * (size_t)side + (size_t)i;
        next[k] = head[c];
        head[c] = (int)k;
    }
    double best = INFINITY;
    for (size_t k = 0; k < n; k++) {
        int i = (int)(p[k].x * side), j = (int)(p[k].y * side);
        for (int dj = -1; dj <= 1; dj++)
            for (int di = -1; di <= 1; di++) {
                int ii = i + di, jj = j + dj;
                if (torus) {
                    ii = (ii + side) % side;
                    jj = (jj + side) % side;
                } else if (ii < 0 || jj < 0 || ii >= side || jj >= side) {
                    continue;
                }
                for (int m = head[(size_t)jj * (size_t)side + (size_t)ii]; m >= 0; m = next[m]) {
                    if ((size_t)m == k)
                        continue;
                    double d = dist2(p[k], p[m], torus);
                    best = d < best ? d : best;
                }
            }
    }
    free(head);
    free(next);
    return sqrt(best);
}

static void test_poisson_fine(void)
{
    struct pt2 *p;
    size_t n = draw_set(SAMPLER_POISSON, 0.3, 5, &p);
    CHECK(n > 60000 && n < 75000);
    CHECK(all_in_unit_square(p, n));
    CHECK(min_distance_bucketed(p, n, 0.003, 0) >= 0.003 * (1 - 1e-12));
    free(p);
}

/* The shift a pooled draw will use: replays sampler_draw's use of the rng. */
static void pool_shift(struct rng rng, int pool_size, uint32_t *pick, double *ox, double *oy)
{
    *pick = rng_below(&rng, (uint32_t)pool_size);
    *ox = rng_uniform(&rng);
    *oy = rng_uniform(&rng);
}

/* Does b equal a shifted by (ox, oy) modulo 1, point by point? */
static int shifted_copy(const struct pt2 *a, size_t na, const struct pt2 *b, size_t nb, double ox, double oy)
{
    if (na != nb)
        return 0;
    for (size_t k = 0; k < na; k++) {
        struct pt2 moved = {fmod(a[k].x + ox, 1.0), fmod(a[k].y + oy, 1.0)};
        if (dist2(moved, b[k], 1) > 1e-24)
            return 0;
    }
    return 1;
}

/* sampler_shift_unit's masked subtraction gives what the plain branch gives, bit for bit, on
   random pairs and at the wrap (p + o at and next to 1), and stays in [0, 1). */
static void test_shift_unit(void)
{
    struct rng g;
    rng_seed(&g, 8, 8);
    int same = 1, in_unit = 1;
    for (int i = 0; i < 1000000; i++) {
        double p = rng_uniform(&g), o = rng_uniform(&g);
        if (i % 4 == 1)
            o = 1.0 - p; /* the sum at 1, or an ulp off it */
        if (i % 4 == 2)
            o = nextafter(1.0 - p, i % 8 == 2 ? 0.0 : 1.0);
        double v = p + o;
        if (v >= 1.0)
            v -= 1.0;
        double want = v >= 1.0 ? 0.0 : v, got = sampler_shift_unit(p, o);
        same &= memcmp(&want, &got, sizeof want) == 0;
        in_unit &= got >= 0 && got < 1;
    }
    CHECK(same);
    CHECK(in_unit);
}

static void test_pool(void)
{
    struct err e;
    const double r = 0.03;
    struct sampler *s = sampler_new(SAMPLER_POISSON, 3, 4, 99, &e);
    CHECK(s != NULL);
    if (!s)
        return;
    size_t cap = sampler_set_capacity(s);
    enum { DRAWS = 24 };
    struct pt2 *sets = malloc(DRAWS * cap * sizeof *sets), *base[4] = {0};
    size_t counts[DRAWS], base_count[4] = {0};
    int inside = 1, apart = 1, covered = 1, matches = 1;
    for (int d = 0; d < DRAWS; d++) {
        struct rng rng;
        rng_seed(&rng, 1000 + (uint64_t)d, 3);
        uint32_t pick;
        double ox, oy;
        pool_shift(rng, 4, &pick, &ox, &oy);
        struct pt2 *p = sets + (size_t)d * cap;
        counts[d] = sampler_draw(s, &rng, p);
        inside &= all_in_unit_square(p, counts[d]);
        if (d < 3) {
            apart &= min_distance(p, counts[d], 1) >= r * (1 - 1e-12);
            covered &= max_gap(p, counts[d], 200, 1) < 2 * r;
        }
        /* undo the shift: draws of the same pool set must agree */
        struct pt2 *unshifted = malloc(counts[d] * sizeof *unshifted);
        for (size_t k = 0; k < counts[d]; k++)
            unshifted[k] = (struct pt2){fmod(p[k].x - ox + 1.0, 1.0), fmod(p[k].y - oy + 1.0, 1.0)};
        if (!base[pick]) {
            base[pick] = unshifted;
            base_count[pick] = counts[d];
        } else {
            matches &= shifted_copy(base[pick], base_count[pick], p, counts[d], ox, oy);
            free(unshifted);
        }
    }
    CHECK(inside);
    CHECK(apart);
    CHECK(covered);
    CHECK(matches);
    int used = 0;
    for (int k = 0; k < 4; k++)
        used += base[k] != NULL;
    CHECK(used >= 3); /* 24 draws over 4 sets */
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++)
            if (base[a] && base[b])
                CHECK(!shifted_copy(base[a], base_count[a], base[b], base_count[b], 0, 0));
    for (int k = 0; k < 4; k++)
        free(base[k]);
    free(sets);
    sampler_free(s);

    /* same pool seed, same pool; t = 100 on the torus: one point (all others within 0.71) */
    struct sampler *s1 = sampler_new(SAMPLER_POISSON, 100, 8, 5, &e);
    int single = s1 != NULL;
    for (uint64_t seed = 0; seed < 50 && single; seed++) {
        struct rng rng;
        struct pt2 one[4];
        rng_seed(&rng, seed, 0);
        single = sampler_draw(s1, &rng, one) == 1 && all_in_unit_square(one, 1);
    }
    CHECK(single);
    sampler_free(s1);

    /* pool_size is ignored by the grid kinds */
    struct sampler *g = sampler_new(SAMPLER_JITTER, 3, 8, 5, &e);
    CHECK(g != NULL && sampler_set_capacity(g) == 1089);
    sampler_free(g);
}

static void test_determinism(void)
{
    for (int k = 0; k < 4; k++) {
        struct pt2 *a, *b, *c;
        size_t na = draw_set((enum sampler_kind)k, 2, 42, &a);
        size_t nb = draw_set((enum sampler_kind)k, 2, 42, &b);
        size_t nc = draw_set((enum sampler_kind)k, 2, 43, &c);
        CHECK(na == nb && memcmp(a, b, na * sizeof *a) == 0);
        if (k != SAMPLER_UNIFORM)
            CHECK(na != nc || memcmp(a, c, na * sizeof *a) != 0);
        free(a);
        free(b);
        free(c);
    }
    /* two pools from one seed are one pool */
    struct err e;
    struct sampler *s1 = sampler_new(SAMPLER_POISSON, 4, 3, 17, &e);
    struct sampler *s2 = sampler_new(SAMPLER_POISSON, 4, 3, 17, &e);
    struct pt2 *a = malloc(sampler_set_capacity(s1) * sizeof *a);
    struct pt2 *b = malloc(sampler_set_capacity(s2) * sizeof *b);
    struct rng r1, r2;
    rng_seed(&r1, 8, 1);
    rng_seed(&r2, 8, 1);
    size_t na = sampler_draw(s1, &r1, a), nb = sampler_draw(s2, &r2, b);
    CHECK(na == nb && memcmp(a, b, na * sizeof *a) == 0);
    free(a);
    free(b);
    sampler_free(s1);
    sampler_free(s2);
}

static void test_bad_input(void)
{
    const double bad[] = {0, -1, 101, NAN, INFINITY, 100.0000001};
    for (int k = 0; k < 4; k++)
        for (int t = 0; t < 6; t++) {
            struct err e = {.msg = ""};
            struct sampler *s = sampler_new((enum sampler_kind)k, bad[t], 0, 0, &e);
            CHECK(s == NULL && strstr(e.msg, "threshold") != NULL);
            sampler_free(s);
        }
    struct err e = {.msg = ""};
    CHECK(sampler_new(SAMPLER_UNIFORM, 0.04, 0, 0, &e) == NULL);
    CHECK(strstr(e.msg, "6250000") != NULL && strstr(e.msg, "4000000") != NULL);
    e.msg[0] = '\0';
    CHECK(sampler_new(SAMPLER_POISSON, 0.05, 0, 0, &e) == NULL);
    CHECK(strstr(e.msg, "8003241") != NULL); /* ceil(sqrt(2) / 0.0005)^2 background cells */
    e.msg[0] = '\0';
    CHECK(sampler_new(SAMPLER_RANDOM, 1e-300, 0, 0, &e) == NULL && e.msg[0] != '\0');
    CHECK(sampler_new((enum sampler_kind)9, 1, 0, 0, &e) == NULL);
    /* exactly at the limit is allowed: n = 2000 */
    struct sampler *s = sampler_new(SAMPLER_UNIFORM, 0.05, 0, 0, &e);
    CHECK(s != NULL && sampler_set_capacity(s) == SAMPLER_MAX_POINTS);
    sampler_free(s);
    sampler_free(NULL);
}

static double quarter_disk(struct pt2 p)
{
    return p.x * p.x + p.y * p.y < QUARTER_DISK_R2 ? 1.0 : 0.0;
}
static double gaussian(struct pt2 p)
{
    return exp(-p.x * p.x - p.y * p.y);
}

struct conv {
    double log_n[4], log_mse[2][4]; /* [disk, gaussian][size] */
};

/* MSE of the mean of the two integrands over sets of (kind, thresholds[i]), seeds[i] sets. */
static struct conv convergence(enum sampler_kind kind, const double thresholds[4], const int seeds[4],
                               int pool_size, uint64_t stream)
{
    struct conv c;
    for (int i = 0; i < 4; i++) {
        struct err e;
        struct sampler *s = sampler_new(kind, thresholds[i], pool_size, 77 + (uint64_t)i, &e);
        struct pt2 *p = malloc(sampler_set_capacity(s) * sizeof *p);
        double se[2] = {0, 0}, points = 0;
        for (int seed = 0; seed < seeds[i]; seed++) {
            struct rng rng;
            rng_seed(&rng, (uint64_t)seed + 1, stream);
            size_t n = sampler_draw(s, &rng, p);
            double disk = 0, gauss = 0;
            for (size_t k = 0; k < n; k++) {
                disk += quarter_disk(p[k]);
                gauss += gaussian(p[k]);
            }
            se[0] += (disk / n - 0.5) * (disk / n - 0.5);
            se[1] += (gauss / n - GAUSS_EXACT) * (gauss / n - GAUSS_EXACT);
            points += n;
        }
        c.log_n[i] = log(points / seeds[i]);
        c.log_mse[0][i] = log(se[0] / seeds[i]);
        c.log_mse[1][i] = log(se[1] / seeds[i]);
        free(p);
        sampler_free(s);
    }
    return c;
}

/* Least-squares slope of log MSE against log N. */
static double slope(const struct conv *c, int f)
{
    double mx = 0, my = 0, sxy = 0, sxx = 0;
    for (int i = 0; i < 4; i++) {
        mx += c->log_n[i] / 4;
        my += c->log_mse[f][i] / 4;
    }
    for (int i = 0; i < 4; i++) {
        sxy += (c->log_n[i] - mx) * (c->log_mse[f][i] - my);
        sxx += (c->log_n[i] - mx) * (c->log_n[i] - mx);
    }
    return sxy / sxx;
}

/* Christensen, Kensler, Kilpatrick 2018, "Progressive Multi-Jittered Sample Sequences": MSE of
   random sets falls as N^-1, of jittered sets as N^-1.5 on a discontinuous integrand and N^-2
   on a smooth one. Poisson-disk sets fall as N^-1 with a lower constant (toroidal and shifted,
   so without the bias of the square domain's denser edges). */
static void test_convergence(void)
{
    const double grid_t[4] = {100.0 / 16, 100.0 / 32, 100.0 / 64, 100.0 / 128};
    /* about 256 ... 16384 points: a toroidal set holds about 6150 / t^2 */
    const double poisson_t[4] = {4.90, 2.45, 1.225, 0.6127};
    const int many[4] = {1024, 1024, 1024, 1024}, fewer[4] = {512, 256, 128, 64};

    struct conv random = convergence(SAMPLER_RANDOM, grid_t, many, 0, 1);
    struct conv jitter = convergence(SAMPLER_JITTER, grid_t, many, 0, 2);
    struct conv poisson = convergence(SAMPLER_POISSON, poisson_t, fewer, 0, 3);
    struct conv pooled = convergence(SAMPLER_POISSON, poisson_t, fewer, 16, 4);

    CHECK_NEAR(slope(&random, 0), -1.0, 0.15);
    CHECK_NEAR(slope(&random, 1), -1.0, 0.15);
    CHECK_NEAR(slope(&jitter, 0), -1.5, 0.15);
    CHECK_NEAR(slope(&jitter, 1), -2.0, 0.15);
    CHECK_NEAR(slope(&poisson, 0), -1.0, 0.15);
    CHECK_NEAR(slope(&poisson, 1), -1.0, 0.15);
    for (int f = 0; f < 2; f++)
        for (int i = 0; i < 4; i++) {
            /* at matching N: poisson_t[i] gives within 2% of grid_t[i]'s count */
            CHECK(fabs(poisson.log_n[i] - random.log_n[i]) < 0.02);
            CHECK(random.log_mse[f][i] - poisson.log_mse[f][i] > log(3.0));
            CHECK(random.log_mse[f][i] - pooled.log_mse[f][i] > log(3.0));
        }

    /* uniform: the midpoint rule, deterministic and accurate on the smooth integrand */
    struct pt2 *p;
    size_t n = draw_set(SAMPLER_UNIFORM, 100.0 / 128, 1, &p);
    double gauss = 0;
    for (size_t k = 0; k < n; k++)
        gauss += gaussian(p[k]);
    CHECK_NEAR(gauss / n, GAUSS_EXACT, 1e-5);
    free(p);
}

/* Cell by cell: uniform cells are sampler_draw's points, jitter points stay inside their cell
   (also at the last cell's far edge), random ones in the square; poisson has no cells. */
/* Cell c's point of sampler s, as the render makes it (sampler_grid_of, sampler_grid_point). */
static struct pt2 cell_point(const struct sampler *s, uint32_t c, struct rng *rng)
{
    const struct sampler_grid g = sampler_grid_of(s);
    return sampler_grid_point(&g, c, rng);
}

static void test_cells(void)
{
    struct err e;
    struct rng rng;
    rng_seed(&rng, 11, 11);
    struct sampler *u = sampler_new(SAMPLER_UNIFORM, 10, 0, 0, &e),
                   *j = sampler_new(SAMPLER_JITTER, 3, 0, 0, &e);
    struct sampler *r = sampler_new(SAMPLER_RANDOM, 5, 0, 0, &e),
                   *p = sampler_new(SAMPLER_POISSON, 5, 0, 0, &e);
    CHECK(u && j && r && p);
    if (!u || !j || !r || !p)
        return;
    CHECK(sampler_cells(u) == 100 && sampler_cells(j) == 33 * 33 && sampler_cells(r) == 400 &&
          sampler_cells(p) == 0);
    CHECK(sampler_kind_of(j) == SAMPLER_JITTER && sampler_kind_of(p) == SAMPLER_POISSON);
    struct pt2 grid[100];
    CHECK(sampler_draw(u, &rng, grid) == 100);
    int same = 1, inside = 1, in_square = 1;
    for (uint32_t c = 0; c < 100; c++) {
        struct pt2 q = cell_point(u, c, &rng);
        same &= q.x == grid[c].x && q.y == grid[c].y;
    }
    for (int k = 0; k < 20000; k++) {
        uint32_t c = k < 100 ? 33 * 33 - 1 : rng_below(&rng, 33 * 33);
        struct pt2 q = cell_point(j, c, &rng);
        inside &= (int)(q.x * 33) == (int)(c % 33) && (int)(q.y * 33) == (int)(c / 33) && q.x < 1 && q.y < 1;
        q = cell_point(r, c, &rng);
        in_square &= q.x >= 0 && q.x < 1 && q.y >= 0 && q.y < 1;
    }
    CHECK(same);
    CHECK(inside);
    /* sampler_grid_of (the render's inline light points): the kind, the side, and each cell's
       point in its column */
    struct sampler *kinds[3] = {u, j, r};
    const int sides[3] = {10, 33, 20};
    int grid_same = 1;
    for (int t = 0; t < 3; t++) {
        struct sampler_grid g = sampler_grid_of(kinds[t]);
        grid_same &= g.kind == sampler_kind_of(kinds[t]) && g.n == sides[t];
        for (uint32_t c = 0; c < sampler_cells(kinds[t]); c++) {
            struct rng a = rng;
            struct pt2 q = sampler_grid_point(&g, c, &a);
            grid_same &= (int)(q.x * g.n) == (int)(c % (uint32_t)g.n) || t == 2;
            rng_u32(&rng);
        }
    }
    CHECK(grid_same);
    CHECK(in_square);
    /* a pooled set taken point by point is sampler_draw's set, from the same rng state */
    struct sampler *pool = sampler_new(SAMPLER_POISSON, 5, 8, 3, &e);
    CHECK(pool && sampler_walk_of(pool) == SAMPLER_WALK_POOL && sampler_walk_of(p) != SAMPLER_WALK_POOL &&
          sampler_walk_of(j) != SAMPLER_WALK_POOL);
    if (pool) {
        struct pt2 *set = malloc(sampler_set_capacity(pool) * sizeof *set);
        struct rng a = rng, b = rng;
        const struct pool_point *src;
        double ox, oy;
        size_t n = sampler_draw(pool, &a, set), m = sampler_pool_set(pool, &b, &src, &ox, &oy);
        int equal = n == m && a.state == b.state;
        for (size_t k = 0; equal && k < n; k++) {
            struct pt2 q = sampler_shift(src[k].p, ox, oy);
            equal &= q.x == set[k].x && q.y == set[k].y;
        }
        CHECK(equal);
        /* the set's turns: cos and sin of 2 pi y of each point, and turned by 2 pi oy those of
           the shifted point's angle, to rounding */
        double so, co, worst = 0;
        int exact = 1;
        v3_sincos_turn(oy, &so, &co);
        for (size_t k = 0; k < n; k++) {
            double sy, cy, ss, cs;
            const struct pt2 t = src[k].turn;
            v3_sincos_turn(src[k].p.y, &sy, &cy);
            exact &= t.x == cy && t.y == sy;
            v3_sincos_turn(set[k].y, &ss, &cs);
            worst = fmax(worst, fabs(t.x * co - t.y * so - cs));
            worst = fmax(worst, fabs(t.y * co + t.x * so - ss));
        }
        CHECK(exact);
        CHECK(worst < 1e-15);
        CHECK(sampler_pool_set(p, &b, &src, &ox, &oy) == 0);
        free(set);
        sampler_free(pool);
    }
    sampler_free(u);
    sampler_free(j);
    sampler_free(r);
    sampler_free(p);
}

/* The seed's cell_coord: (i + u) / n, moved by ulps until strictly inside cell i. */
static double ref_cell_coord(int i, double u, int n)
{
    double v = (i + u) / n;
    while (v >= 1.0 || (int)(v * n) > i)
        v = nextafter(v, 0.0);
    while ((int)(v * n) < i)
        v = nextafter(v, 1.0);
    return v;
}

/* Jitter points, set by set and cell by cell, bit for bit the seed's formula: cell % n and cell / n
   (sampler_grid_point divides by a multiply and shift), two rng_uniform draws each (the sampler
   draws them by jump-ahead), the quotient's repair, for grid sides 1 to 2000. */
static void test_jitter_exact(void)
{
    const double thresholds[] = {100, 40, 16.6, 12.5, 7, 3, 0.7, 0.33, 0.07, 0.05};
    int same_cells = 1, same_sets = 1;
    struct rng g;
    rng_seed(&g, 5, 5);
    for (int t = 0; t < (int)(sizeof thresholds / sizeof thresholds[0]); t++) {
        struct err e;
        struct sampler *s = sampler_new(SAMPLER_JITTER, thresholds[t], 0, 0, &e);
        CHECK(s != NULL);
        if (!s)
            continue;
        const int n = sampler_grid_side(thresholds[t]);
        const uint32_t cells = sampler_cells(s);
        for (int k = 0; k < 20000; k++) {
            uint32_t c = k < 2 * n ? (k < n ? (uint32_t)(k * n + n - 1) : cells - 1 - (uint32_t)(k - n))
                                   : rng_below(&g, cells);
            struct rng a = g, b = g;
            struct pt2 q = cell_point(s, c, &a);
            double u = rng_uniform(&b), v = rng_uniform(&b);
            double x = ref_cell_coord((int)(c % (uint32_t)n), u, n),
                   y = ref_cell_coord((int)(c / (uint32_t)n), v, n);
            same_cells &=
                memcmp(&q.x, &x, sizeof x) == 0 && memcmp(&q.y, &y, sizeof y) == 0 && a.state == b.state;
            rng_u32(&g);
        }
        if (n <= 100) {
            struct pt2 *set = malloc(sampler_set_capacity(s) * sizeof *set);
            struct rng a = g, b = g;
            size_t m = set ? sampler_draw(s, &a, set) : 0;
            same_sets &= m == cells;
            for (size_t k = 0; k < m; k++) {
                double u = rng_uniform(&b), v = rng_uniform(&b);
                double x = ref_cell_coord((int)(k % (size_t)n), u, n),
                       y = ref_cell_coord((int)(k / (size_t)n), v, n);
                same_sets &= memcmp(&set[k].x, &x, sizeof x) == 0 && memcmp(&set[k].y, &y, sizeof y) == 0;
            }
            same_sets &= a.state == b.state;
            free(set);
        }
        sampler_free(s);
    }
    CHECK(same_cells);
    CHECK(same_sets);
}

int main(void)
{
    test_jitter_exact();
    test_cells();
    test_names_and_sizes();
    test_grid_counts();
    test_poisson_counts();
    test_poisson_disks();
    test_poisson_fine();
    test_shift_unit();
    test_pool();
    test_determinism();
    test_bad_input();
    test_convergence();
    return check_report("test_sampler");
}
