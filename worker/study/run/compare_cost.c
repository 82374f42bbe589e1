/* compare_cost: the cost design (blocks of shuffled timed units), the render order, cost.csv. */
#include "compare_cost.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fileio.h"
#include "base/hash.h"
#include "base/rng.h"
#include "base/sbuf.h"
#include "study/judge/compare_stats.h"
#include "study/load/verdict_csv.h"

/* Fisher-Yates over n indices with a generator seeded from the study's name and key. */
static void shuffle(const struct compare *c, uint64_t key, int *idx, int n)
{
    struct rng r;
    rng_seed(&r, hash_u64(hash_bytes(HASH_FNV_OFFSET, c->name, strlen(c->name)), key), 0x636f7374);
    for (int i = n - 1; i > 0; i--) {
        int j = (int)rng_below(&r, (uint32_t)i + 1), t = idx[i];
        idx[i] = idx[j], idx[j] = t;
    }
}

void compare_cost_order(const struct compare *c, int *order)
{
    int per = c->n_seeds > 0 ? c->n_items / c->n_seeds : 0, n = 0;
    for (int k = 0; k < c->n_seeds; k++) {
        int *run = order + n;
        for (int s = 0; s < c->n_scenes; s++)
            for (int v = 0; v < c->n_variants; v++)
                for (int p = 0; p < c->n_points; p++)
                    order[n++] = compare_index(c, s, v, p, k);
        shuffle(c, 0x6f72646572ULL + (uint64_t)k, run, per);
    }
}

/* How one (variant, point) is timed: `reps` whole images, or every row_parts-th row of one. */
struct design {
    int reps, row_parts;
    double image_samples; /* the point's mean camera samples per image (over its seeds) */
};

/* Scene s's designs. The work of a unit follows the CPU seconds of the point's images, averaged over
   every (variant, point) of identical settings (their first seed's resume hash): variants that are
   the same are timed by the same design, so no part of a unit's fixed overhead tells them apart. */
static void designs(const struct compare *c, int s, struct design *d)
{
    int nv = c->n_variants, np = c->n_points, h = c->scenes[s].height;
    for (int i = 0; i < nv * np; i++) {
        uint64_t key = c->results.rows[compare_index(c, s, i / np, i % np, 0)].hash;
        double cpu = 0;
        int n = 0;
        struct compare_agg a; /* means over the seeds */
        for (int j = 0; j < nv * np; j++)
            if (j == i || (key && c->results.rows[compare_index(c, s, j / np, j % np, 0)].hash == key)) {
                compare_stats_aggregate(c, s, j / np, j % np, &a);
                cpu += a.cpu_s, n++;
            }
        cpu /= n;
        compare_stats_aggregate(c, s, i / np, i % np, &a);
        d[i].image_samples = a.spp * c->scenes[s].width * h; /* camera samples per image */
        d[i].reps = 1, d[i].row_parts = 1;
        if (cpu >= COMPARE_COST_UNIT_S)
            d[i].row_parts = (int)fmin(h, fmax(1, lround(cpu / COMPARE_COST_UNIT_S)));
        else
            d[i].reps = cpu > 0 ? (int)fmin(COMPARE_COST_REPS_MAX, fmax(1, lround(COMPARE_COST_UNIT_S / cpu)))
                                : COMPARE_COST_REPS_MAX;
    }
}

/* What the timed renders of one scene share: its scene, camera and a framebuffer thrown away. */
struct timing {
    struct scene_file sf;
    struct camera cam;
    float *rgb;
    int scene, w, h, processes; /* scene: its index in the study */
    const volatile sig_atomic_t *stop;
};

/* Time (variant v, point p) once in block b: the CPU seconds one image of the point costs. */
static int time_unit(const struct compare *c, struct timing *t, int v, int p, int b, const struct design *d,
                     double *cost, struct err *e)
{
    const int s = t->scene;
    double cpu = 0, samples = 0;
    for (int r = 0; r < d->reps; r++) {
        const struct job *j = &c->items[compare_index(c, s, v, p, 0)].job;
        uint64_t seed = c->seeds[((size_t)b * d->reps + r) % (size_t)c->n_seeds];
        struct sampler *pix = NULL, *light = NULL;
        struct procs_result res;
        int rc = -1;
        if (render_spec_samplers_new(&j->spec, seed, &pix, &light, e) == 0) {
            struct procs_job fj = {.scene = t->sf.scene,
                                   .camera = &t->cam,
                                   .rs = render_spec_settings(&j->spec, t->w, t->h, seed),
                                   .pixel = pix,
                                   .light = light,
                                   .processes = t->processes > 0 ? t->processes : j->processes,
                                   .row_part = b % d->row_parts,
                                   .row_parts = d->row_parts,
                                   .stop = t->stop};
            rc = procs_render_here(&fj, t->rgb, &res, e);
        }
        sampler_free(pix);
        sampler_free(light);
        if (rc < 0)
            return -1;
        cpu += res.cpu_s, samples += (double)res.total.samples;
    }
    *cost = samples > 0 ? cpu / samples * d->image_samples : NAN;
    return 0;
}

/* Scene s's blocks: each times every (variant, point) once, in an order of its own. */
static int measure_scene(const struct compare *c, struct study_results *r, int s, const struct run_opts *o,
                         struct err *e)
{
    int n = c->n_variants * c->n_points, rc = -1;
    struct design *d = calloc((size_t)n, sizeof *d);
    int *idx = calloc((size_t)n, sizeof *idx);
    struct timing t = {.scene = s, .processes = o->processes, .stop = o->stop};
    const struct compare_scene *cs = &c->scenes[s];
    if (!d || !idx) {
        err_set(e, NULL, 0, 0, "out of memory");
        goto done;
    }
    designs(c, s, d);
    if (scene_load_src(&cs->input->src, &t.sf, e) < 0)
        goto done;
    t.w = cs->width, t.h = cs->height;
    if (camera_init(&t.cam, &t.sf.camera, (double)t.w / t.h, e) < 0 ||
        !(t.rgb = procs_framebuffer_new(t.w, t.h, e)))
        goto done;
    for (int b = 0; b < r->n_blocks; b++) {
        for (int i = 0; i < n; i++)
            idx[i] = i;
        shuffle(c, ((uint64_t)s << 32) | (uint64_t)b, idx, n);
        for (int i = 0; i < n; i++) {
            int v = idx[i] / c->n_points, p = idx[i] % c->n_points;
            if (time_unit(c, &t, v, p, b, &d[idx[i]], &r->cost_s[compare_cost_index(c, s, v, p, b)], e) < 0)
                goto done;
        }
    }
    rc = 0;
done:
    procs_framebuffer_free(t.rgb, t.w, t.h);
    scene_file_free(&t.sf);
    free(d);
    free(idx);
    return rc;
}

int compare_cost_measure(const struct compare *c, struct study_results *r, const struct run_opts *o,
                         struct err *e)
{
    free(r->cost_s);
    r->n_blocks = COMPARE_COST_BLOCKS;
    r->cost_s = calloc((size_t)c->n_scenes * c->n_variants * c->n_points * r->n_blocks, sizeof *r->cost_s);
    if (!r->cost_s) {
        r->n_blocks = 0;
        return err_set(e, NULL, 0, 0, "out of memory");
    }
    for (int s = 0; s < c->n_scenes; s++)
        if (measure_scene(c, r, s, o, e) < 0) {
            free(r->cost_s);
            r->cost_s = NULL, r->n_blocks = 0;
            err_prefix(e, c->name);
            return -1;
        }
    return 0;
}

/* A point's name in cost.csv: its first seed's image without "-s<seed>.<ext>". */
static void point_name(const struct compare *c, int s, int v, int p, char *buf, size_t n)
{
    snprintf(buf, n, "%s", c->items[compare_index(c, s, v, p, 0)].job.output);
    char *dash = strrchr(buf, '-');
    if (dash && dash[1] == 's')
        *dash = 0;
}

char *compare_cost_csv(const struct compare *c)
{
    struct sbuf b = {0};
    char name[JOB_PATH_MAX];
    sbuf_printf(&b, "scene,variant,point,block,cpu_s\n");
    for (int s = 0; s < c->n_scenes; s++)
        for (int v = 0; v < c->n_variants; v++)
            for (int p = 0; p < c->n_points; p++) {
                point_name(c, s, v, p, name, sizeof name);
                for (int k = 0; k < c->results.n_blocks; k++) /* letters, digits, - and _: no quoting */
                    sbuf_printf(&b, "%s,%s,%s,%d,%.6g\n", c->scenes[s].name, c->variants[v], name, k,
                                c->results.cost_s[compare_cost_index(c, s, v, p, k)]);
            }
    return sbuf_take(&b);
}

/* The (scene, variant, point) of c whose names are these, as an index into n * points; -1. */
static int find_cell(const struct compare *c, const char *scene, const char *variant, const char *point)
{
    char name[JOB_PATH_MAX];
    for (int s = 0; s < c->n_scenes; s++)
        for (int v = 0; v < c->n_variants && !strcmp(c->scenes[s].name, scene); v++)
            for (int p = 0; p < c->n_points && !strcmp(c->variants[v], variant); p++) {
                point_name(c, s, v, p, name, sizeof name);
                if (!strcmp(name, point))
                    return (s * c->n_variants + v) * c->n_points + p;
            }
    return -1;
}

int compare_cost_read(const struct compare *c, struct study_results *res, const char *dir)
{
    char path[4096];
    uint8_t *data = NULL;
    size_t len;
    struct err ignored;
    struct verdict_csv t = {0};
    int cells = c->n_scenes * c->n_variants * c->n_points, blocks = 0, rc = -1;
    snprintf(path, sizeof path, "%s/cost.csv", dir);
    if (fileio_read_all(path, 64u << 20, &data, &len, &ignored) < 0)
        return -1;
    double *cost = malloc(sizeof *cost * (size_t)cells * COMPARE_COST_BLOCKS);
    static const char *const head[5] = {"scene", "variant", "point", "block", "cpu_s"};
    if (!cost || verdict_csv_parse(&t, (char *)data, len, path, &ignored) < 0 || t.n_rows < 1 ||
        t.n_fields != 5)
        goto done;
    for (int i = 0; i < 5; i++)
        if (strcmp(t.rows[0][i], head[i]))
            goto done;
    for (int i = 0; i < cells * COMPARE_COST_BLOCKS; i++)
        cost[i] = NAN;
    for (int r = 1; r < t.n_rows; r++) {
        char *const *f = t.rows[r];
        long k = strtol(f[3], NULL, 10);
        double x = strtod(f[4], NULL);
        int cell = find_cell(c, f[0], f[1], f[2]);
        if (cell < 0 || k < 0 || k >= COMPARE_COST_BLOCKS || !(x > 0 && isfinite(x)))
            goto done; /* a row of another study or a damaged file: not guessed at */
        cost[(size_t)cell * COMPARE_COST_BLOCKS + (size_t)k] = x;
        blocks = (int)fmax(blocks, (double)k + 1);
    }
    for (int i = 0; i < cells * blocks; i++) { /* in place, `blocks` a cell: never ahead of what it reads */
        cost[i] = cost[(size_t)(i / blocks) * COMPARE_COST_BLOCKS + (size_t)(i % blocks)];
        if (!isfinite(cost[i]))
            goto done;
    }
    if (blocks < 2)
        goto done;
    free(res->cost_s);
    res->cost_s = cost; /* taken over */
    res->n_blocks = blocks;
    cost = NULL;
    rc = 0;
done:
    verdict_csv_free(&t);
    free(cost);
    free(data);
    return rc;
}
