/* bvh_build: binned surface-area-heuristic build (Wald 2007, "On fast construction of SAH-based
   bounding volume hierarchies") down to single prims, collapsed into a flat array of wide nodes
   (Dammertz et al. 2008, "Shallow bounding volume hierarchies for fast SIMD ray tracing") by the
   cost-optimal plan of Ylitie et al. 2017, which also picks the leaves. */
#include "bvh.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#define BVH_BINS 12
#define BVH_LEAF_MAX 4
/* SAH splits down to this depth; below it ranges are halved down to single prims, which takes
   fewer than 32 more levels for any int count (BVH_DEPTH in all). */
#define BVH_SAH_DEPTH (BVH_DEPTH - 32)

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

/* The binary SAH tree, built first and then collapsed into BVH_WIDTH-wide nodes. */
struct bnode {
    struct box box;
    int left, right; /* interior: children; leaf: -1 */
    int start, count;
};

/* The collapse's plan for binary node b (Ylitie et al. 2017, "Efficient incoherent ray traversal
   on GPUs through compressed wide BVHs", section 3.1): cost[j] is the least expected cost of its
   subtree held in at most j lanes of the wide parent (SAH: each part weighted by its box area),
   with left[j] lanes for the left child's subtree and right[j] for the right's, or left[j] = 0:
   the node in one lane, a leaf when `leaf`, else a wide node of its own, whose lanes are
   node_left's for the left child's subtree and node_right's for the right's. */
struct plan {
    double cost[BVH_WIDTH + 1];
    int8_t left[BVH_WIDTH + 1], right[BVH_WIDTH + 1];
    int8_t leaf, node_left, node_right;
};

struct build {
    struct scene *sc;
    struct box *boxes;
    vec3 *centroids;
    int32_t *order;
    struct bnode *bin;
    struct plan *plan;
    int n_bin;
    struct bvh_node *nodes;
    int n_nodes;
};

/* Find the best binned split of order[start..start+count); returns axis or -1 for a leaf. */
static int best_split(struct build *bd, int start, int count, struct box bounds, double *split_at)
{
    struct box cb = box_empty();
    for (int i = start; i < start + count; i++)
        cb = box_join(cb, (struct box){bd->centroids[bd->order[i]], bd->centroids[bd->order[i]]});
    double best = INFINITY; /* always split: plan_node picks the leaves */
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

/* Binary node over order[start..start+count); returns its index in bd->bin. */
static int build_binary(struct build *bd, int start, int count, int depth)
{
    int idx = bd->n_bin++;
    struct bnode *node = &bd->bin[idx];
    node->box = box_empty();
    for (int i = start; i < start + count; i++)
        node->box = box_join(node->box, bd->boxes[bd->order[i]]);
    node->left = node->right = -1;
    node->start = start;
    node->count = count;
    double split = 0;
    int ax = -1;
    if (count > 1 && depth < BVH_SAH_DEPTH)
        ax = best_split(bd, start, count, node->box, &split);
    if (count == 1)
        return idx;
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
    if (mid == start || mid == start + count) /* no useful split: halve the range */
        mid = start + count / 2;
    int left = build_binary(bd, start, mid - start, depth + 1);
    int right = build_binary(bd, mid, start + count - mid, depth + 1);
    bd->bin[idx].left = left;
    bd->bin[idx].right = right;
    return idx;
}

/* Lane c of node n holds box b, rounded outward so the float box encloses the double one. */
static void set_lane(struct bvh_node *n, int c, struct box b)
{
    double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
    for (int a = 0; a < 3; a++) {
        n->lo[a][c] = nextafterf((float)lo[a], -INFINITY);
        n->hi[a][c] = nextafterf((float)hi[a], INFINITY);
    }
}

/* The plan's costs, in visits of an 8-wide node (two 4-lane slab tests and the loop around
   them): a leaf lane met, and a prim tested inline in the traversal (spheres, rects, media whose
   flight is computed when met) or through shape_hit. Measured on final: other ratios (0.3 / 1.0,
   0.8 / 2.0, a leaf 0.05-0.5) gave the same trees within 1% of instructions. */
#define COST_NODE 1.0
#define COST_LEAF 0.1
#define COST_FAST 0.5
#define COST_SLOW 1.5

/* Fill bd->plan[b] from its children's plans, for nodes of `width` lanes. */
static void plan_node(struct build *bd, int b, int width)
{
    const struct bnode *k = &bd->bin[b];
    struct plan *pl = &bd->plan[b];
    double area = box_area(k->box);
    double leaf = INFINITY, node = INFINITY;
    if (k->count <= BVH_LEAF_MAX) {
        leaf = COST_LEAF;
        for (int i = k->start; i < k->start + k->count; i++)
            leaf += bvh_prim_kind(&bd->sc->prims[bd->order[i]]) == BVH_LEAF_SHAPE ? COST_SLOW : COST_FAST;
        leaf *= area;
    }
    memset(pl->left, 0, sizeof pl->left);
    memset(pl->right, 0, sizeof pl->right);
    for (int j = 1; j <= width; j++)
        pl->cost[j] = INFINITY;
    if (k->left >= 0) { /* the best split of j lanes between the children, for every j */
        const struct plan *l = &bd->plan[k->left], *r = &bd->plan[k->right];
        for (int j = 2; j <= width; j++)
            for (int s = 1; s < j; s++)
                if (l->cost[s] + r->cost[j - s] < pl->cost[j]) {
                    pl->cost[j] = l->cost[s] + r->cost[j - s];
                    pl->left[j] = (int8_t)s;
                    pl->right[j] = (int8_t)(j - s);
                }
        node = area * COST_NODE + pl->cost[width];
    }
    pl->node_left = pl->left[width];
    pl->node_right = pl->right[width];
    pl->leaf = leaf <= node;
    pl->cost[1] = leaf <= node ? leaf : node;
    for (int j = 2; j <= width; j++)
        if (!(pl->cost[j] < pl->cost[j - 1])) { /* j lanes do no better than j - 1 */
            pl->cost[j] = pl->cost[j - 1];
            pl->left[j] = pl->left[j - 1];
            pl->right[j] = pl->right[j - 1];
        }
}

/* Append to lanes the binary nodes that hold b's subtree in at most j lanes; the new count. */
static int plan_lanes(const struct build *bd, int b, int j, int *lanes, int n)
{
    const struct plan *pl = &bd->plan[b];
    if (pl->left[j] == 0) {
        lanes[n] = b;
        return n + 1;
    }
    n = plan_lanes(bd, bd->bin[b].left, pl->left[j], lanes, n);
    return plan_lanes(bd, bd->bin[b].right, pl->right[j], lanes, n);
}

/* A new node of n lanes, all empty (never hit); its index. */
static int node_new(struct build *bd, int n)
{
    struct bvh_node *node = &bd->nodes[bd->n_nodes];
    memset(node, 0, sizeof *node);
    for (int c = 0; c < BVH_WIDTH; c++)
        for (int a = 0; a < 3; a++)
            node->lo[a][c] = INFINITY, node->hi[a][c] = -INFINITY;
    node->quads = (uint8_t)((n + 3) / 4);
    return bd->n_nodes++;
}

/* Lane c of node n is binary node k's leaf: its prims and kind (bvh_node.kind); a one-prim leaf
   the traversal dispatches by kind names its prim: one load fewer. */
static void set_leaf(const struct build *bd, struct bvh_node *n, int c, const struct bnode *k)
{
    n->count[c] = (uint16_t)k->count;
    n->leaves |= (uint16_t)(1u << c);
    n->kind[c] = k->count != 1 ? BVH_LEAF_ANY : (uint8_t)bvh_prim_kind(&bd->sc->prims[bd->order[k->start]]);
    n->child[c] = n->kind[c] == BVH_LEAF_ANY ? k->start : bd->order[k->start];
}

/* Wide node for binary interior node b as planned; its index. */
static int collapse(struct build *bd, int b)
{
    const struct plan *pl = &bd->plan[b];
    int kids[BVH_WIDTH], n = plan_lanes(bd, bd->bin[b].left, pl->node_left, kids, 0);
    n = plan_lanes(bd, bd->bin[b].right, pl->node_right, kids, n);
    int idx = node_new(bd, n);
    struct bvh_node *node = &bd->nodes[idx];
    for (int c = 0; c < n; c++) {
        const struct bnode *k = &bd->bin[kids[c]];
        set_lane(node, c, k->box);
        if (bd->plan[kids[c]].leaf)
            set_leaf(bd, node, c, k);
    }
    for (int c = 0; c < n; c++)
        if (!bd->plan[kids[c]].leaf) {
            int child = collapse(bd, kids[c]); /* bd->nodes is allocated up front */
            bd->nodes[idx].child[c] = child;
        }
    return idx;
}

int bvh_build(struct scene *sc, struct err *e)
{
    int n = sc->n_prims;
    struct build bd = {sc, NULL, NULL, NULL, NULL, NULL, 0, NULL, 0};
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
    bd.bin = malloc((size_t)(2 * n) * sizeof *bd.bin);
    bd.plan = malloc((size_t)(2 * n) * sizeof *bd.plan);
    /* a wide node per binary interior node at most, each on its own cache lines */
    bd.nodes = aligned_alloc(64, (size_t)n * sizeof *bd.nodes);
    if (!bd.boxes || !bd.centroids || !bd.order || !bd.bin || !bd.plan || !bd.nodes) {
        free(bd.plan);
        free(bd.order);
        free(bd.nodes);
        free(bd.bin);
        free(bd.boxes);
        free(bd.centroids);
        return err_set(e, NULL, 0, 0, "out of memory building the BVH of %d primitives", n);
    }
    for (int i = 0; i < n; i++) {
        shape_bounds(&sc->prims[i], &bd.boxes[i].lo, &bd.boxes[i].hi);
        bd.centroids[i] = v3_scale(v3_add(bd.boxes[i].lo, bd.boxes[i].hi), 0.5);
        bd.order[i] = i;
    }
    build_binary(&bd, 0, n, 0);
    if (bd.bin[0].left < 0) { /* a scene of one prim: a root with one child */
        struct bvh_node *root = &bd.nodes[node_new(&bd, 1)];
        set_lane(root, 0, bd.bin[0].box);
        set_leaf(&bd, root, 0, &bd.bin[0]);
    } else {
        /* A scene of at most 16 prims (the Cornell boxes: 8 and 15, a prim per lane) in one
           node: one visit per ray, its leaves tested nearest-hit-culled in one pass. Elsewhere
           8-wide: 16 lanes deep in a big tree test more boxes than they save visits (final +4%;
           a 16-wide root alone: +1%). */
        int width = n <= BVH_WIDTH ? BVH_WIDTH : BVH_WIDTH / 2;
        for (int b = bd.n_bin - 1; b >= 0; b--) /* children follow their parent */
            plan_node(&bd, b, width);
        collapse(&bd, 0);
    }
    free(bd.boxes);
    free(bd.centroids);
    free(bd.bin);
    free(bd.plan);
    sc->nodes = bd.nodes;
    sc->n_nodes = bd.n_nodes;
    sc->prim_order = bd.order;
    return 0;
}
