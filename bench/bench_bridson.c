/* bench_bridson: microseconds per point of Bridson Poisson-disk sets, fresh and from a pool, and of
   Owen-scrambled Sobol sets for comparison, in CPU time (the machine is shared: wall time would
   count other people's work). */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "sample/sampler.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median over `runs` timings of drawing `sets` sets of kind; prints one JSON object line. */
static void bench(enum sampler_kind kind, double t, int pool, int runs, int sets)
{
    struct err e;
    struct sampler *s = sampler_new(kind, t, pool, 1, &e);
    if (!s) {
        fprintf(stderr, "bench_bridson: %s\n", e.msg);
        exit(1);
    }
    struct pt2 *out = malloc(sampler_set_capacity(s) * sizeof *out);
    double us[32];
    size_t points = 0;
    struct rng r;
    rng_seed(&r, 7, 7);
    for (int k = 0; k < runs; k++) {
        double t0 = now_s();
        size_t n = 0;
        for (int i = 0; i < sets; i++)
            n += sampler_draw(s, &r, out);
        us[k] = (now_s() - t0) * 1e6 / n;
        points = n / sets;
    }
    qsort(us, runs, sizeof us[0], cmp);
    printf("{\"threshold\": %g, \"pool\": %d, \"points_per_set\": %zu, \"runs\": %d, "
           "\"us_per_point_median\": %.4f, \"us_per_point_min\": %.4f, \"us_per_point_max\": %.4f, "
           "\"sampler\": \"%s\"}\n",
           t, pool, points, runs, us[runs / 2], us[0], us[runs - 1], sampler_kind_name(kind));
    free(out);
    sampler_free(s);
}

int main(void)
{
    bench(SAMPLER_POISSON, 1, 0, 9, 20);
    bench(SAMPLER_POISSON, 0.25, 0, 9, 2);
    bench(SAMPLER_POISSON, 1, 64, 9, 200);
    bench(SAMPLER_SOBOL, 1, 0, 9, 200);
    bench(SAMPLER_SOBOL, 6.25, 0, 9, 20000);
    return 0;
}
