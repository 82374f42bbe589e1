/* bvh: binned surface-area-heuristic build (Wald 2007, "On fast construction of SAH-based
   bounding volume hierarchies") into a flat node array; iterative slab-test traversal. */
#include "bvh.h"

#include <float.h>
#include <stdlib.h>

#define BVH_BINS 12
#define BVH_LEAF_MAX 4
#define BVH_STACK 64

struct box {
    vec3 lo, hi;
};

static struct box box_empty(void)
{
    return (struct box){v3(DBL_MAX, DBL_MAX, DBL_MAX), v3(-DBL_MAX, -DBL_MAX, -DBL_MAX)};
}
static struct box box_join(struct box a, struct box b)
{
    return (struct box){v3_min(a.lo, b.lo), v3_max(a.hi, b.hi)};
}
static double box_area(struct box b)
{
    vec3 d = v3_sub(b.hi, b.lo);
    if (d.x < 0)
        return 0;
    return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

struct build {
    struct scene *sc;
    struct box *boxes;
    vec3 *centroids;
    int32_t *order;
    struct bvh_node *nodes;
    int n_nodes;
};

static void set_node_box(struct bvh_node *n, struct box b)
{
    /* Round outward so float boxes still enclose the double-precision geometry. */
    double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
    for (int i = 0; i < 3; i++) {
        n->lo[i] = nextafterf((float)lo[i], -FLT_MAX);
        n->hi[i] = nextafterf((float)hi[i], FLT_MAX);
    }
}

/* Find the best binned split of order[start..start+count); returns axis or -1 for a leaf. */
static int best_split(struct build *bd, int start, int count, struct box bounds, double *split_at)
{
    struct box cb = box_empty();
    for (int i = start; i < start + count; i++)
        cb = box_join(cb, (struct box){bd->centroids[bd->order[i]], bd->centroids[bd->order[i]]});
    double best = box_area(bounds) * count; /* cost of a leaf, in units of one intersection */
    int best_axis = -1;
    for (int ax = 0; ax < 3; ax++) {
        double lo = v3_get(cb.lo, ax), hi = v3_get(cb.hi, ax);
        if (hi - lo < 1e-12)
            continue;
        struct box bins[BVH_BINS];
        int cnt[BVH_BINS] = {0};
        for (int b = 0; b < BVH_BINS; b++)
            bins[b] = box_empty();
        double scale = BVH_BINS / (hi - lo);
        for (int i = start; i < start + count; i++) {
            int p = bd->order[i];
            int b = (int)((v3_get(bd->centroids[p], ax) - lo) * scale);
            b = b < 0 ? 0 : b >= BVH_BINS ? BVH_BINS - 1 : b;
            cnt[b]++;
            bins[b] = box_join(bins[b], bd->boxes[p]);
        }
        double right_area[BVH_BINS];
        int right_cnt[BVH_BINS];
        struct box acc = box_empty();
        int n = 0;
        for (int b = BVH_BINS - 1; b > 0; b--) {
            acc = box_join(acc, bins[b]);
            n += cnt[b];
            right_area[b] = box_area(acc);
            right_cnt[b] = n;
        }
        acc = box_empty();
        n = 0;
        for (int b = 0; b < BVH_BINS - 1; b++) {
            acc = box_join(acc, bins[b]);
            n += cnt[b];
            if (n == 0 || right_cnt[b + 1] == 0)
                continue;
            double cost = 0.125 * box_area(bounds) + box_area(acc) * n + right_area[b + 1] * right_cnt[b + 1];
            if (cost < best) {
                best = cost;
                best_axis = ax;
                *split_at = lo + (b + 1) / scale;
            }
        }
    }
    return best_axis;
}

static int build_node(struct build *bd, int start, int count, int depth)
{
    int idx = bd->n_nodes++;
    struct box bounds = box_empty();
    for (int i = start; i < start + count; i++)
        bounds = box_join(bounds, bd->boxes[bd->order[i]]);
    struct bvh_node *node = &bd->nodes[idx];
    set_node_box(node, bounds);
    double split = 0;
    int ax = -1;
    if (count > 1 && depth < BVH_STACK - 2)
        ax = best_split(bd, start, count, bounds, &split);
    if (ax < 0 && count <= BVH_LEAF_MAX) {
        node->start = start;
        node->count = count;
        return idx;
    }
    int mid = start;
    if (ax >= 0) {
        for (int i = start; i < start + count; i++) {
            if (v3_get(bd->centroids[bd->order[i]], ax) < split) {
                int32_t t = bd->order[i];
                bd->order[i] = bd->order[mid];
                bd->order[mid++] = t;
            }
        }
    }
    if (mid == start || mid == start + count) { /* no useful split: halve the range */
        if (depth >= BVH_STACK - 2) {
            node->start = start;
            node->count = count;
            return idx;
        }
        mid = start + count / 2;
    }
    node->count = 0;
    build_node(bd, start, mid - start, depth + 1);
    int right = build_node(bd, mid, start + count - mid, depth + 1);
    bd->nodes[idx].start = right;
    bd->nodes[idx].count = 0;
    return idx;
}

int bvh_build(struct scene *sc, struct err *e)
{
    int n = sc->n_prims;
    struct build bd = {sc, NULL, NULL, NULL, NULL, 0};
    free(sc->nodes);
    free(sc->prim_order);
    sc->nodes = NULL;
    sc->prim_order = NULL;
    sc->n_nodes = 0;
    if (n == 0)
        return 0;
    bd.boxes = malloc((size_t)n * sizeof *bd.boxes);
    bd.centroids = malloc((size_t)n * sizeof *bd.centroids);
    bd.order = malloc((size_t)n * sizeof *bd.order);
    bd.nodes = malloc((size_t)(2 * n) * sizeof *bd.nodes);
    if (!bd.boxes || !bd.centroids || !bd.order || !bd.nodes) {
        free(bd.order);
        free(bd.nodes);
        free(bd.boxes);
        free(bd.centroids);
        return err_set(e, NULL, 0, 0, "out of memory building the BVH of %d primitives", n);
    }
    for (int i = 0; i < n; i++) {
        shape_bounds(&sc->prims[i], &bd.boxes[i].lo, &bd.boxes[i].hi);
        bd.centroids[i] = v3_scale(v3_add(bd.boxes[i].lo, bd.boxes[i].hi), 0.5);
        bd.order[i] = i;
    }
    build_node(&bd, 0, n, 0);
    free(bd.boxes);
    free(bd.centroids);
    sc->nodes = bd.nodes;
    sc->n_nodes = bd.n_nodes;
    sc->prim_order = bd.order;
    return 0;
}

/* Slab test against multiplications by the precomputed inverse direction. */
static int box_hit(const struct bvh_node *n, const double o[3], const double inv[3], double t0, double t1)
{
    for (int a = 0; a < 3; a++) {
        double ta = (n->lo[a] - o[a]) * inv[a];
        double tb = (n->hi[a] - o[a]) * inv[a];
        if (ta > tb) {
            double t = ta;
            ta = tb;
            tb = t;
        }
        t0 = ta > t0 ? ta : t0;
        t1 = tb < t1 ? tb : t1;
        if (t1 < t0)
            return 0;
    }
    return 1;
}

int bvh_hit(const struct scene *sc, const ray *r, double t_min, double t_max, struct hit *h)
{
    if (sc->n_nodes == 0)
        return 0;
    double o[3] = {r->orig.x, r->orig.y, r->orig.z};
    double inv[3] = {1.0 / r->dir.x, 1.0 / r->dir.y, 1.0 / r->dir.z};
    int stack[BVH_STACK];
    int sp = 0, got = 0;
    int node = 0;
    for (;;) {
        const struct bvh_node *n = &sc->nodes[node];
        if (box_hit(n, o, inv, t_min, t_max)) {
            if (n->count > 0) {
                for (int i = n->start; i < n->start + n->count; i++) {
                    int p = sc->prim_order[i];
                    if (shape_hit(&sc->prims[p], r, t_min, t_max, h)) {
                        t_max = h->t;
                        h->prim = p;
                        got = 1;
                    }
                }
            } else {
                stack[sp++] = n->start;
                node = node + 1;
                continue;
            }
        }
        if (sp == 0)
            break;
        node = stack[--sp];
    }
    return got;
}
