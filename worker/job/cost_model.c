/* cost_model: a render's CPU time from a pilot's cost per traced sample and the timed cost of
   each point set it draws (cost_model.h). */
#include "cost_model.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "cost_sets.h"
#include "render/render.h"

/* The share of a pilot's time a set timing may take (one set at least): a few sets. */
#define COST_SET_TARGET_S 0.004
/* Past its budget a model still gives each new pilot COST_PILOT_MIN_S (a few paths), each set timing
   one batch; past COST_OVER times it, new set sizes are scaled, new pilots trace one path. */
#define COST_OVER 1.5
#define COST_PILOT_MIN_S 0.0005

/* What a pilot's traced samples cost depends on: the scene and view, the path's settings, the light
   sampler's kind, and under sampler_dims: all the pixel sampler and its set size (to a factor of 2:
   the padded slots a pixel reaches). Thresholds do not enter otherwise: their sets are timed apart. */
struct pilot_key {
    const struct scene_file *sf;
    int width, height, max_depth, light_sampling;
    enum integrator integrator;
    int dims, roulette;
    enum sampler_kind light_kind, dims_kind;
    int dims_size; /* sampler_dims: all: log2 of the pixel set's capacity (the slots a pixel reaches) */
    int pooled;
};

/* A pilot's figures, per pixel or per traced sample, means over its pixels. */
struct pilot_fig {
    double trace_s;      /* CPU seconds a traced sample costs, its point-set draws taken out */
    double light_points; /* light points a sample takes */
    double light_sets;   /* light sets a pixel draws at the pilot's sizes (the lights it uses) */
    double padded_sets;  /* padded slots a pixel's samples reach */
    int pixels;
    double samples, traced;
};

struct pilot_entry {
    struct pilot_key key;
    struct pilot_fig fig;
    int measured; /* 0: expected (cost_model_expect), not run yet */
};

struct cost_model {
    double budget_s, spent_s;
    struct cost_sets *sets;
    struct pilot_entry *pilots;
    int n_pilots, cap_pilots;
};

struct cost_model *cost_model_new(double budget_s)
{
    struct cost_model *m = calloc(1, sizeof *m);
    if (!m || !(m->sets = cost_sets_new())) {
        free(m);
        return NULL;
    }
    m->budget_s = budget_s;
    return m;
}

void cost_model_free(struct cost_model *m)
{
    if (!m)
        return;
    cost_sets_free(m->sets);
    free(m->pilots);
    free(m);
}

/* Pixels k of n of a w x h image, spread over it: one per band of rows, at golden-ratio steps
   across (a pixel's cost depends on what it sees). */
static void pilot_pixel(int k, int n, int w, int h, int *x, int *y)
{
    *y = (int)((k + 0.5) * h / n);
    *x = (int)(fmod((k + 0.5) * 0.6180339887498949, 1.0) * w);
}

/* The threshold at which the pilot draws kind's sets: t, or coarser when its sets are larger
   than COST_PILOT_SET_MAX points. */
static double pilot_threshold(enum sampler_kind kind, double t)
{
    return (double)sampler_capacity(kind, t) <= COST_PILOT_SET_MAX
               ? t
               : cost_sets_threshold_for(kind, t, COST_PILOT_SET_MAX);
}

/* How long a set timing may take: COST_SET_TARGET_S, then one batch past the budget, 0 past
   COST_OVER times the budget (cost_sets then scales a timed set of the kind, or draws one). */
static double set_target(const struct cost_model *m)
{
    return m->spent_s < m->budget_s ? COST_SET_TARGET_S : m->spent_s < COST_OVER * m->budget_s ? 1e-9 : 0;
}

/* A pilot's progress: the paths the next call may trace, the time spent, the counted pixels. */
struct pilot_run {
    double budget_s, spent_s, paths;
    double clock_s; /* clock_pair_s */
    size_t cap;
    struct cost_set pixel, light, padded; /* what the pilot's own set draws cost (pilot_draws) */
    struct pilot_fig sum;
};

/* What reading a thread's CPU clock twice costs (a system call each): the least of a few pairs.
   A one-sample pixel takes a few of them. */
static double clock_pair_s(void)
{
    double least = HUGE_VAL;
    for (int i = 0; i < 16; i++) {
        const double a = clock_s(CLOCK_THREAD_CPUTIME_ID), b = clock_s(CLOCK_THREAD_CPUTIME_ID);
        least = b - a < least ? b - a : least;
    }
    return least;
}

/* Render pixel (x, y) at most p->cap paths, timed whole, once (the same pixel again runs faster than
   a render's do: a 20-point Poisson set in 6 us, fresh 10); count it when it is whole or the budget
   is spent, else leave it to be rendered again with more paths. The cap starts at one path and
   grows at most 8 times a call, to what the budget left would pay: however costly a path is (a
   whole pixel of 100000 stacked pyramids took 22 s), the pilot stays near its budget. The sets the
   call drew are taken out at their timed cost: what is left is tracing. */
static void pilot_step(struct pilot_run *p, struct render_ctx *ctx, int x, int y, int n_lights)
{
    struct render_stats st;
    float rgb[3];
    render_stats_init(&st);
    st.pixels = 1; /* untimed inside: render_time.h times a pixel whose stats count 8k pixels */
    const double t0 = clock_s(CLOCK_THREAD_CPUTIME_ID);
    const size_t all = render_pixel_paths(ctx, x, y, p->cap, rgb, &st);
    const double dt_clock = clock_s(CLOCK_THREAD_CPUTIME_ID) - t0 - p->clock_s,
                 dt = dt_clock > 0 ? dt_clock : 0;
    const size_t done = all < p->cap ? all : p->cap;
    const double draws = p->pixel.s_per_set + (double)st.light_sets * p->light.s_per_set +
                         (double)st.padded_sets * p->padded.s_per_set;
    const double trace = dt > draws ? dt - draws : 0;
    p->spent_s += dt;
    p->paths += (double)done;
    const double per_path = p->paths > 0 ? p->spent_s / p->paths : 0;
    const double afford = per_path > 0 ? (p->budget_s - p->spent_s) / per_path : HUGE_VAL;
    const size_t grown = p->cap > SIZE_MAX / 8 ? SIZE_MAX : p->cap * 8;
    const size_t cap = afford < (double)grown ? (afford < 1 ? 1 : (size_t)afford) : grown;
    p->cap = cap;
    if (done < all && cap > done)
        return; /* again, with more of its paths */
    const double traced = done ? (double)done : 1;
    p->sum.pixels++;
    p->sum.samples += (double)all;
    p->sum.traced += (double)done;
    p->sum.trace_s += trace; /* divided by the paths traced at the end: a ratio of sums */
    p->sum.light_points += (double)st.light_points / traced;
    p->sum.light_sets += (double)(st.light_sets < (uint64_t)n_lights ? st.light_sets : (uint64_t)n_lights);
    p->sum.padded_sets += (double)st.padded_sets;
}

/* The cost of the pilot's own sets of j into p: its pixel sampler at pixel_t (as a pixel's and as a
   padded set), its light sampler at light_t. 0 or -1. */
static int pilot_draws(struct cost_model *m, const struct job *j, double pixel_t, double light_t,
                       struct pilot_run *p, struct err *e)
{
    const struct cost_sampler px = {j->spec.pixel.kind, pixel_t, j->spec.poisson_pool > 0,
                                    j->spec.poisson_domain},
                              li = {j->spec.light.kind, light_t, j->spec.poisson_pool > 0,
                                    j->spec.poisson_domain};
    /* timed, never scaled (at most COST_PILOT_SET_MAX points): what is left of a call is tracing */
    const double target = set_target(m) > 0 ? set_target(m) : 1e-9;
    if (cost_sets_get(m->sets, &px, COST_SET_PIXEL, target, &p->pixel, &m->spent_s, e) < 0 ||
        (j->spec.dims_all &&
         cost_sets_get(m->sets, &px, COST_SET_PADDED, target, &p->padded, &m->spent_s, e) < 0) ||
        (!j->spec.dims_all && j->spec.light_sampling &&
         cost_sets_get(m->sets, &li, COST_SET_LIGHT, target, &p->light, &m->spent_s, e) < 0))
        return -1;
    return 0;
}

/* Run the pilot of j (key k) within budget_s CPU seconds into *fig. 0 or -1 with e filled. */
static int pilot(struct cost_model *m, const struct job *j, const struct pilot_key *k, double budget_s,
                 struct pilot_fig *fig, struct err *e)
{
    struct camera cam;
    struct sampler *pix = NULL, *light = NULL;
    struct render_ctx *ctx = NULL;
    const struct scene_file *sf = k->sf;
    int rc = -1;
    if (camera_init(&cam, &sf->camera, (double)k->width / k->height, e) < 0) {
        snprintf(e->file, sizeof e->file, "%s", j->scene_path);
        return -1;
    }
    const int pool =
        j->spec.poisson_pool > 0; /* one set: a draw from a pool costs the same whatever its size */
    const double pixel_t = pilot_threshold(j->spec.pixel.kind, j->spec.pixel.threshold),
                 light_t = pilot_threshold(j->spec.light.kind, j->spec.light.threshold);
    /* an image of fewer pixels than a pilot renders: the same view at a multiple of its size, so
       that the pilot's samples still come from COST_PILOT_PIXELS pixels */
    int scale = 1;
    while ((long)k->width * k->height * scale * scale < COST_PILOT_PIXELS)
        scale++;
    const int w = k->width * scale, h = k->height * scale;
    const struct render_settings rs = render_spec_settings(&j->spec, w, h, j->spec.seed);
    struct pilot_run p = {.budget_s = budget_s, .cap = 1, .clock_s = clock_pair_s()};
    if (pilot_draws(m, j, pixel_t, light_t, &p, e) < 0)
        goto done;
    const double t0 = clock_s(CLOCK_THREAD_CPUTIME_ID);
    if (!(pix = sampler_new(j->spec.pixel.kind, pixel_t, pool, 1, e)) ||
        !(light = sampler_new(j->spec.light.kind, light_t, pool, 2, e))) {
        snprintf(e->file, sizeof e->file, "%s", j->path);
        goto spent;
    }
    sampler_set_domain(pix, j->spec.poisson_domain);
    sampler_set_domain(light, j->spec.poisson_domain);
    if (!(ctx = render_ctx_new(sf->scene, &cam, &rs, pix, light, e)))
        goto spent;
    const long pixels = (long)w * h;
    const int n = pixels < COST_PILOT_PIXELS ? (int)pixels : COST_PILOT_PIXELS;
    while (p.sum.pixels < n && (p.sum.pixels == 0 || p.spent_s < budget_s)) {
        int x, y;
        pilot_pixel(p.sum.pixels, n, w, h, &x, &y);
        pilot_step(&p, ctx, x, y, sf->scene->n_lights);
    }
    const double np = p.sum.pixels;
    *fig = p.sum; /* sums: the trace time per traced sample, the rest per pixel */
    fig->trace_s /= p.sum.traced > 0 ? p.sum.traced : 1;
    fig->light_points /= np;
    fig->light_sets /= np;
    fig->padded_sets /= np;
    rc = 0;
spent:
    m->spent_s += clock_s(CLOCK_THREAD_CPUTIME_ID) - t0;
done:
    render_ctx_free(ctx);
    sampler_free(pix);
    sampler_free(light);
    return rc;
}

static int key_equal(const struct pilot_key *a, const struct pilot_key *b)
{
    return a->sf == b->sf && a->width == b->width && a->height == b->height && a->max_depth == b->max_depth &&
           a->light_sampling == b->light_sampling && a->integrator == b->integrator && a->dims == b->dims &&
           a->roulette == b->roulette && a->light_kind == b->light_kind && a->dims_kind == b->dims_kind &&
           a->dims_size == b->dims_size && a->pooled == b->pooled;
}

/* The entry of key k, added (not measured) when there is none; NULL on no memory. */
static struct pilot_entry *entry_for(struct cost_model *m, const struct pilot_key *k)
{
    for (int i = 0; i < m->n_pilots; i++)
        if (key_equal(&m->pilots[i].key, k))
            return &m->pilots[i];
    if (m->n_pilots == m->cap_pilots) {
        int cap = m->cap_pilots ? 2 * m->cap_pilots : 16;
        struct pilot_entry *grown = realloc(m->pilots, (size_t)cap * sizeof *grown);
        if (!grown)
            return NULL;
        m->pilots = grown;
        m->cap_pilots = cap;
    }
    m->pilots[m->n_pilots] = (struct pilot_entry){.key = *k};
    return &m->pilots[m->n_pilots++];
}

/* The pilot of j's key: shared when one ran, else run now with its share of the budget left
   (an equal share with every pilot expected and not run yet). */
static int pilot_for(struct cost_model *m, const struct job *j, const struct pilot_key *k,
                     struct pilot_fig *fig, struct err *e)
{
    struct pilot_entry *p = entry_for(m, k);
    if (!p)
        return err_set(e, NULL, 0, 0, "out of memory for the cost model");
    if (!p->measured) {
        int waiting = 0;
        for (int i = 0; i < m->n_pilots; i++)
            waiting += !m->pilots[i].measured;
        const double left = m->budget_s - m->spent_s;
        double share = left > 0 ? left / waiting : 0;
        if (share < COST_PILOT_MIN_S && m->spent_s < COST_OVER * m->budget_s)
            share = COST_PILOT_MIN_S;
        if (pilot(m, j, k, share, &p->fig, e) < 0)
            return -1;
        p->measured = 1;
    }
    *fig = p->fig;
    return 0;
}

/* A set's cost from the cache, or timed now when the budget allows (else scaled from a cached
   one of its kind when there is one). */
static int set_cost(struct cost_model *m, const struct job *j, int light, enum cost_set_use use,
                    struct cost_set *out, struct err *e)
{
    const struct sampler_spec *s = light ? &j->spec.light : &j->spec.pixel;
    const struct cost_sampler sp = {s->kind, s->threshold, j->spec.poisson_pool > 0, j->spec.poisson_domain};
    if (cost_sets_get(m->sets, &sp, use, set_target(m), out, &m->spent_s, e) < 0) {
        snprintf(e->file, sizeof e->file, "%s", j->path);
        return -1;
    }
    return 0;
}

/* The pilot key of j's render at width x height of sf. */
static struct pilot_key key_of(const struct job *j, const struct scene_file *sf, int width, int height)
{
    return (struct pilot_key){
        sf,
        width,
        height,
        j->spec.max_depth,
        j->spec.light_sampling,
        j->spec.integrator,
        j->spec.dims_all,
        render_spec_roulette(&j->spec),
        j->spec.light.kind,
        j->spec.dims_all ? j->spec.pixel.kind : SAMPLER_RANDOM,
        j->spec.dims_all ? ilogb((double)sampler_capacity(j->spec.pixel.kind, j->spec.pixel.threshold)) : 0,
        j->spec.poisson_pool > 0};
}

int cost_model_expect(struct cost_model *m, const struct job *j, const struct scene_file *sf, int width,
                      int height, struct err *e)
{
    const struct pilot_key k = key_of(j, sf, width, height);
    return entry_for(m, &k) ? 0 : err_set(e, NULL, 0, 0, "out of memory for the cost model");
}

int cost_model_estimate(struct cost_model *m, const struct job *j, const struct scene_file *sf, int width,
                        int height, struct cost_estimate *out, struct err *e)
{
    memset(out, 0, sizeof *out);
    const struct pilot_key k = key_of(j, sf, width, height);
    struct pilot_fig fig = {0};
    struct cost_set pix, light = {0}, pad = {0};
    if (pilot_for(m, j, &k, &fig, e) < 0 || set_cost(m, j, 0, COST_SET_PIXEL, &pix, e) < 0)
        return -1;
    const double pixels = (double)width * height;
    out->spp_mean = pix.points;
    out->samples = pix.points * pixels;
    out->ns_per_sample = fig.trace_s * 1e9;
    out->trace_s = out->samples * fig.trace_s;
    out->pixel_sets_s = pixels * pix.s_per_set;
    if (fig.light_points > 0 && !j->spec.dims_all) {
        if (set_cost(m, j, 1, COST_SET_LIGHT, &light, e) < 0)
            return -1;
        /* the lights a pixel uses draw one set each, more when its samples take more points */
        const double taken = fig.light_points * pix.points, used = fig.light_sets > 0 ? fig.light_sets : 1;
        const double per_pixel =
            light.points > 0 && taken / light.points > used ? taken / light.points : used;
        out->light_sets = per_pixel * pixels;
        out->light_sets_s = out->light_sets * light.s_per_set;
    }
    if (j->spec.dims_all && fig.padded_sets > 0) {
        if (set_cost(m, j, 0, COST_SET_PADDED, &pad, e) < 0)
            return -1;
        out->padded_sets = fig.padded_sets * pixels;
        out->padded_sets_s = out->padded_sets * pad.s_per_set;
    }
    out->cpu_s = out->trace_s + out->pixel_sets_s + out->light_sets_s + out->padded_sets_s;
    out->sets_scaled = pix.scaled || light.scaled || pad.scaled;
    out->pilot_pixels = fig.pixels;
    out->pilot_samples = fig.samples;
    out->pilot_traced = fig.traced;
    return 0;
}
