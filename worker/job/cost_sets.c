/* cost_sets: one point set's cost, timed on this machine (cost_sets.h). */
#include "cost_sets.h"

#include <math.h>
#include <stdlib.h>

#include "base/clock.h"
#include "base/rng.h"
#include "sample/padding.h"
#include "sample/stream.h"

/* Most sets one timing draws: a cheap set (one point) is drawn many times between two clock
   reads, whose own cost (a system call for a thread's CPU clock) would be most of its time. */
#define COST_SETS_MAX_DRAWS 4096
/* A timing's least CPU time, so that the two clock reads around it are a small part of it. */
#define COST_SETS_MIN_S 20e-6

struct cost_entry {
    struct cost_sampler sp;
    enum cost_set_use use;
    struct cost_set cost;
};

struct cost_sets {
    struct cost_entry *e;
    int n, cap;
};

struct cost_sets *cost_sets_new(void)
{
    return calloc(1, sizeof(struct cost_sets));
}

void cost_sets_free(struct cost_sets *c)
{
    if (!c)
        return;
    free(c->e);
    free(c);
}

/* What a timing loop draws with: the sampler and the buffers of one use. */
struct drawer {
    struct sampler *s;
    struct pt2 *pts;
    struct stream_source src;
    struct stream st;
    struct padding pad;
    size_t pixel_n; /* padded: the pixel's count a slot is filled to */
};

/* One set drawn as `use` (k: its index, a pixel of its own); returns its points. */
static size_t draw_one(struct drawer *d, enum cost_set_use use, struct rng *rng, int k)
{
    if (use == COST_SET_LIGHT) {
        stream_restart(&d->st);
        stream_refill(&d->src, &d->st, rng);
        return d->st.n;
    }
    if (use == COST_SET_PADDED) {
        padding_pixel(&d->pad, 1, k, 0, d->pixel_n);
        padding_fill(&d->pad, 0);
        return d->pixel_n;
    }
    const struct sampler_at at = {1, k, 0, 0};
    return sampler_draw_at(d->s, rng, &at, d->pts);
}

/* Time sets of sp at threshold t drawn as `use`: about target_s CPU seconds (at most
   COST_SETS_MAX_DRAWS sets, one at least). */
static int time_at(const struct cost_sampler *sp, double t, enum cost_set_use use, double target_s,
                   struct cost_set *out, double *spent_s, struct err *e)
{
    struct drawer d = {0};
    struct rng rng;
    rng_seed(&rng, 0x636f7374ULL, 1);
    const double t0 = clock_s(CLOCK_THREAD_CPUTIME_ID);
    int rc = -1;
    /* a pool of one set: a draw from a pool costs the same whatever its size */
    if (!(d.s = sampler_new(sp->kind, t, sp->pooled ? 1 : 0, 0x706f6f6cULL, e)))
        goto done;
    sampler_set_domain(d.s, sp->domain);
    if (!(d.pts = malloc(sampler_set_capacity(d.s) * sizeof *d.pts)) ||
        (use == COST_SET_LIGHT &&
         (stream_source_init(&d.src, d.s, e) < 0 || stream_init(&d.st, &d.src) < 0))) {
        err_set(e, NULL, 0, 0, "out of memory timing point sets");
        goto done;
    }
    if (use == COST_SET_PADDED) {
        const struct sampler_at at = {1, 0, 0, 0};
        d.pixel_n = sampler_draw_at(d.s, &rng, &at, d.pts);
        if (padding_init(&d.pad, d.s, 1, e) < 0)
            goto done;
    }
    /* one set untimed first: its workspace's first touch (page faults) is the render's once a
       process, not once a set; it took 10 us of a 6 us pixel's 20-point Poisson set */
    draw_one(&d, use, &rng, 0);
    double points = 0;
    int n = 0;
    const double start = clock_s(CLOCK_THREAD_CPUTIME_ID);
    double spent = 0;
    /* batches of 1, 2, 4, ... sets between clock reads, for COST_SETS_MIN_S at least unless
       target_s is 0 */
    const double until = target_s > 0 && target_s < COST_SETS_MIN_S ? COST_SETS_MIN_S : target_s;
    for (int batch = 1; n == 0 || (spent < until && n < COST_SETS_MAX_DRAWS); batch *= 2) {
        for (int b = 0; b < batch; b++, n++)
            points += (double)draw_one(&d, use, &rng, n + 1);
        spent = clock_s(CLOCK_THREAD_CPUTIME_ID) - start;
    }
    *out = (struct cost_set){spent / n, points / n, 0};
    rc = 0;
done:
    stream_release(&d.st);
    stream_source_release(&d.src);
    padding_release(&d.pad);
    free(d.pts);
    sampler_free(d.s);
    *spent_s += clock_s(CLOCK_THREAD_CPUTIME_ID) - t0;
    return rc;
}

double cost_sets_threshold_for(enum sampler_kind kind, double t, double points)
{
    const double cap = (double)sampler_capacity(kind, t), scaled = t * sqrt(cap / points);
    return scaled < 100 ? scaled : 100;
}

/* A set too large to draw: timed at two smaller sizes, its cost a power of the capacity between
   1 (a cost per point) and 2 (the exponent the two sizes give), its points in proportion. */
static int time_scaled(const struct cost_sampler *sp, enum cost_set_use use, double target_s,
                       struct cost_set *out, double *spent_s, struct err *e)
{
    /* both sizes past a table the kind keeps (pmj02bn's): the sets drawn fresh cost another way */
    const double table = (double)sampler_table_points(sp->kind),
                 small = table > 0 ? 2 * table : COST_SETS_SMALL,
                 large = table > 0 ? 4 * table : COST_SETS_DIRECT_MAX;
    const double t1 = cost_sets_threshold_for(sp->kind, sp->threshold, small),
                 t2 = cost_sets_threshold_for(sp->kind, sp->threshold, large);
    struct cost_set a, b;
    if (time_at(sp, t1, use, target_s / 2, &a, spent_s, e) < 0 ||
        time_at(sp, t2, use, target_s / 2, &b, spent_s, e) < 0)
        return -1;
    const double cap = (double)sampler_capacity(sp->kind, sp->threshold),
                 cap1 = (double)sampler_capacity(sp->kind, t1), cap2 = (double)sampler_capacity(sp->kind, t2);
    double power = cap2 > cap1 && a.s_per_set > 0 && b.s_per_set > 0
                       ? log(b.s_per_set / a.s_per_set) / log(cap2 / cap1)
                       : 1;
    power = power < 1 ? 1 : power > 2 ? 2 : power;
    *out = (struct cost_set){b.s_per_set * pow(cap / cap2, power), b.points * cap / cap2, 1};
    return 0;
}

/* Whether x is a set of sp's kind drawn as `use`, at any threshold. */
static int same_kind(const struct cost_entry *x, const struct cost_sampler *sp, enum cost_set_use use)
{
    return x->use == use && x->sp.kind == sp->kind && x->sp.pooled == sp->pooled &&
           x->sp.domain == sp->domain;
}

/* Out of time: the cached set of the same kind and use nearest in capacity, scaled in
   proportion to the capacity. 1 when there was one. */
static int borrow(const struct cost_sets *c, const struct cost_sampler *sp, enum cost_set_use use,
                  struct cost_set *out)
{
    const double cap = (double)sampler_capacity(sp->kind, sp->threshold);
    double best = HUGE_VAL;
    for (int i = 0; i < c->n; i++) {
        const struct cost_entry *x = &c->e[i];
        if (!same_kind(x, sp, use))
            continue;
        const double r = cap / (double)sampler_capacity(x->sp.kind, x->sp.threshold);
        if (fabs(log(r)) < best) {
            best = fabs(log(r));
            *out = (struct cost_set){x->cost.s_per_set * r, x->cost.points * r, 1};
        }
    }
    return best < HUGE_VAL;
}

int cost_sets_get(struct cost_sets *c, const struct cost_sampler *sp, enum cost_set_use use, double target_s,
                  struct cost_set *out, double *spent_s, struct err *e)
{
    for (int i = 0; i < c->n; i++)
        if (same_kind(&c->e[i], sp, use) && c->e[i].sp.threshold == sp->threshold) {
            *out = c->e[i].cost;
            return 0;
        }
    if (target_s <= 0 && borrow(c, sp, use, out))
        return 0;
    if (c->n == c->cap) {
        int cap = c->cap ? 2 * c->cap : 16;
        struct cost_entry *grown = realloc(c->e, (size_t)cap * sizeof *grown);
        if (!grown)
            return err_set(e, NULL, 0, 0, "out of memory for the cost model");
        c->e = grown;
        c->cap = cap;
    }
    const size_t cap = sampler_capacity(sp->kind, sp->threshold), table = sampler_table_points(sp->kind);
    int rc = cap > (table > 0 ? 4 * table : COST_SETS_DIRECT_MAX)
                 ? time_scaled(sp, use, target_s, out, spent_s, e)
                 : time_at(sp, sp->threshold, use, target_s, out, spent_s, e);
    if (rc < 0)
        return -1;
    c->e[c->n++] = (struct cost_entry){*sp, use, *out};
    return 0;
}
