/* bvh: iterative traversal of the wide BVH (bvh_build.c) that tests a node's child boxes four
   at a time with SIMD slab tests and visits the hit children nearest first. */
#include "bvh.h"
#include "base/simd.h"
#include "shape_inline.h"

#include <string.h>

/* A wide node is visited at most once per level and pushes at most BVH_WIDTH - 1 children. */
#define BVH_STACK ((BVH_WIDTH - 1) * BVH_DEPTH + 1)

/* Four floats in one vector register (a GCC/Clang extension; scalar code without SIMD). */
typedef float bvh_f4 __attribute__((vector_size(16)));
typedef int32_t bvh_i4 __attribute__((vector_size(16)));

static inline bvh_f4 f4_load(const void *p)
{
    bvh_f4 x;
    memcpy(&x, p, sizeof x);
    return x;
}
static inline bvh_f4 f4_splat(float x)
{
    return (bvh_f4){x, x, x, x};
}

/* max(a, b) and min(a, b) lane by lane, b where a is NaN: a NaN slab (a zero direction
   component with the origin on the plane) then constrains nothing. SSE's maxps/minps have
   exactly this rule; the generic form compiles to four instructions instead of one. */
#if SIMD_SSE
#include <xmmintrin.h>
static inline bvh_f4 f4_max(bvh_f4 a, bvh_f4 b)
{
    return (bvh_f4)_mm_max_ps((__m128)a, (__m128)b);
}
static inline bvh_f4 f4_min(bvh_f4 a, bvh_f4 b)
{
    return (bvh_f4)_mm_min_ps((__m128)a, (__m128)b);
}
static inline int f4_mask(bvh_i4 m)
{
    return _mm_movemask_ps((__m128)m);
}
#else
static inline bvh_f4 f4_max(bvh_f4 a, bvh_f4 b)
{
    bvh_i4 m = a > b;
    return (bvh_f4)(((bvh_i4)a & m) | ((bvh_i4)b & ~m));
}
static inline bvh_f4 f4_min(bvh_f4 a, bvh_f4 b)
{
    bvh_i4 m = a < b;
    return (bvh_f4)(((bvh_i4)a & m) | ((bvh_i4)b & ~m));
}
static inline int f4_mask(bvh_i4 m)
{
    return (m[0] & 1) | (m[1] & 2) | (m[2] & 4) | (m[3] & 8);
}
#endif

/* The ray in float for the slab tests. Rounding the origin o to float would move it by up to
   |o| 2^-24 per axis and could make the test miss a box the ray meets, so each axis gets two
   float origins instead, |o| 2^-23 to either side (still on their side after rounding): the
   near plane's distance is measured from the one that makes it smallest, the far plane's from
   the one that makes it largest. The slabs' own rounding is covered by scaling the far distance
   by 1 + 2^-20 (> 1 + 2 gamma_3, Ize 2013, "Robust BVH ray traversal"). Near and far planes are
   chosen once per ray by the direction's sign bits (-0 included), as byte offsets into a node. */
struct fray {
    bvh_f4 o_near[3], o_far[3], inv[3];
    size_t near[3], far[3];
};

static inline void fray_axis(struct fray *fr, int a, double o, double d)
{
    const size_t lo = offsetof(struct bvh_node, lo) + (size_t)a * BVH_WIDTH * sizeof(float);
    const size_t hi = offsetof(struct bvh_node, hi) + (size_t)a * BVH_WIDTH * sizeof(float);
    const size_t neg = signbit(d) != 0;
    /* t = (plane - o) / d falls as o grows when d > 0: the near distance from o + shift. The
       sign comes from d by copysign and the planes by arithmetic, not by branches, which a
       random direction's signs would mispredict half the time. */
    double shift = copysign(fabs(o) * 0x1.0p-23, d);
    fr->o_near[a] = f4_splat((float)(o + shift));
    fr->o_far[a] = f4_splat((float)(o - shift));
    fr->inv[a] = f4_splat((float)(1.0 / d));
    fr->near[a] = lo + neg * (hi - lo);
    fr->far[a] = hi - neg * (hi - lo);
}

static inline void fray_init(struct fray *fr, const ray *r)
{
    fray_axis(fr, 0, r->orig.x, r->dir.x);
    fray_axis(fr, 1, r->orig.y, r->dir.y);
    fray_axis(fr, 2, r->orig.z, r->dir.z);
}

/* The far distances' scale factor in fray_init's slab tests (see there). */
#define BVH_GROW (1.0f + 0x1.0p-20f)

#if SIMD_SSE
#include <emmintrin.h>

/* The near and far planes' byte offsets for the direction's sign bits m (bit a: axis a negative),
   as fray_axis picks them. */
#define FRAY_LO(a) (offsetof(struct bvh_node, lo) + (size_t)(a)*BVH_WIDTH * sizeof(float))
#define FRAY_HI(a) (offsetof(struct bvh_node, hi) + (size_t)(a)*BVH_WIDTH * sizeof(float))
#define FRAY_NEAR(a, m) ((m) >> (a)&1 ? FRAY_HI(a) : FRAY_LO(a))
#define FRAY_FAR(a, m) ((m) >> (a)&1 ? FRAY_LO(a) : FRAY_HI(a))
#define FRAY_PLANES(m)                                                                                       \
    {                                                                                                        \
        {FRAY_NEAR(0, m), FRAY_NEAR(1, m), FRAY_NEAR(2, m)},                                                 \
        {                                                                                                    \
            FRAY_FAR(0, m), FRAY_FAR(1, m), FRAY_FAR(2, m)                                                   \
        }                                                                                                    \
    }
static const struct {
    size_t near[3], far[3];
} fray_planes[8] = {FRAY_PLANES(0), FRAY_PLANES(1), FRAY_PLANES(2), FRAY_PLANES(3),
                    FRAY_PLANES(4), FRAY_PLANES(5), FRAY_PLANES(6), FRAY_PLANES(7)};

/* Lane i of v in all four lanes, for sel = 0x55 i (pshufd: no copy first, as shufps needs). */
#define f4_lane(v, sel) ((bvh_f4)_mm_shuffle_epi32(_mm_castps_si128(v), (sel)))

/* fray_init for the one-node traversal (the tree keeps fray_init), the three axes at once in
   float vectors. The origin is rounded to float first (off by at most |o| 2^-24) and then
   shifted by |o| 2^-22 + 2^-100 to either side in float, which leaves both shifted origins on
   their side of o after rounding (the 2^-100 for a tiny o, whose float may be a denormal). The
   inverse direction is an IEEE division, not rcpps's estimate: CPUs differ in the estimate's
   bits, and the order in which boxes are visited must not depend on the CPU; its sign bits are
   d's and pick the planes from a table. */
static inline void fray_init_sse(struct fray *fr, const ray *r)
{
    __m128d oxy = _mm_loadu_pd(&r->orig.x), oz = _mm_load_sd(&r->orig.z);
    __m128d dxy = _mm_loadu_pd(&r->dir.x), dz = _mm_load_sd(&r->dir.z);
    __m128 o = _mm_movelh_ps(_mm_cvtpd_ps(oxy), _mm_cvtpd_ps(oz));
    __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), _mm_movelh_ps(_mm_cvtpd_ps(dxy), _mm_cvtpd_ps(dz)));
    static const bvh_f4 sign = {-0.0f, -0.0f, -0.0f, -0.0f}, scale = {0x1.0p-22f, 0x1.0p-22f, 0x1.0p-22f, 0},
                        tiny = {0x1.0p-100f, 0x1.0p-100f, 0x1.0p-100f, 0};
    __m128 shift = _mm_add_ps(_mm_mul_ps(_mm_andnot_ps((__m128)sign, o), (__m128)scale), (__m128)tiny);
    shift = _mm_or_ps(shift, _mm_and_ps((__m128)sign, inv));
    __m128 o_near = _mm_add_ps(o, shift), o_far = _mm_sub_ps(o, shift);
    fr->o_near[0] = f4_lane(o_near, 0x00), fr->o_near[1] = f4_lane(o_near, 0x55),
    fr->o_near[2] = f4_lane(o_near, 0xaa);
    fr->o_far[0] = f4_lane(o_far, 0x00), fr->o_far[1] = f4_lane(o_far, 0x55),
    fr->o_far[2] = f4_lane(o_far, 0xaa);
    fr->inv[0] = f4_lane(inv, 0x00), fr->inv[1] = f4_lane(inv, 0x55), fr->inv[2] = f4_lane(inv, 0xaa);
    int m = _mm_movemask_ps(inv) & 7;
    memcpy(fr->near, fray_planes[m].near, sizeof fr->near);
    memcpy(fr->far, fray_planes[m].far, sizeof fr->far);
}
/* A slab's two distances share their axis's rcpps error, but the axes' errors differ: near <=
   far needs a margin of twice that error and the rounding on top (also on the float bound of
   t_max). A box's entry distance may then come out up to 2^-11 too far, which only delays the
   nearest-hit cull of a leaf by as much. */
#define NODE_GROW (1.0f + 0x1.0p-9f)
#else
#define fray_init_sse fray_init
#define NODE_GROW BVH_GROW
#endif

/* Entry distances into the four child boxes of quad m (a node's address plus the quad's
   offset), into tn[0..3]; returns one bit per child hit. */
static inline int quad_test(const struct fray *fr, const char *m, bvh_f4 t_lo, float t_hi, float *tn,
                            float grow)
{
    bvh_f4 tn0 = (f4_load(m + fr->near[0]) - fr->o_near[0]) * fr->inv[0];
    bvh_f4 tn1 = (f4_load(m + fr->near[1]) - fr->o_near[1]) * fr->inv[1];
    bvh_f4 tn2 = (f4_load(m + fr->near[2]) - fr->o_near[2]) * fr->inv[2];
    bvh_f4 tf0 = (f4_load(m + fr->far[0]) - fr->o_far[0]) * fr->inv[0];
    bvh_f4 tf1 = (f4_load(m + fr->far[1]) - fr->o_far[1]) * fr->inv[1];
    bvh_f4 tf2 = (f4_load(m + fr->far[2]) - fr->o_far[2]) * fr->inv[2];
    bvh_f4 near = f4_max(tn2, f4_max(tn1, f4_max(tn0, t_lo)));
    bvh_f4 far = f4_min(tf2, f4_min(tf1, f4_min(tf0, f4_splat(t_hi))));
    memcpy(tn, &near, sizeof near);
    return f4_mask(near <= far * f4_splat(grow));
}

/* Entry distances into node n's child boxes (its quads in use, one to four), into tn[]; returns
   one bit per child hit. Unrolled: the branches on the count go the same way for every ray of a
   scene, and a loop cost more (its counter, shifts by a variable count, the planes' addresses
   set up in registers before it). */
static inline int node_test(const struct fray *fr, const char *n, int quads, bvh_f4 t_lo, float t_hi,
                            float *tn, float grow)
{
    const size_t q = sizeof(bvh_f4);
    int hit = quad_test(fr, n, t_lo, t_hi, tn, grow);
    if (quads > 1) {
        hit |= quad_test(fr, n + q, t_lo, t_hi, tn + 4, grow) << 4;
        if (quads > 2) {
            hit |= quad_test(fr, n + 2 * q, t_lo, t_hi, tn + 8, grow) << 8;
            if (quads > 3)
                hit |= quad_test(fr, n + 3 * q, t_lo, t_hi, tn + 12, grow) << 12;
        }
    }
    return hit;
}

/* node_test for a tree's nodes: 8-wide (bvh_build.c), both quads tested without a loop or a
   branch (a node's unused lanes are empty boxes, which no ray hits). */
static inline int node_test8(const struct fray *fr, const char *n, bvh_f4 t_lo, float t_hi, float *tn)
{
    return quad_test(fr, n, t_lo, t_hi, tn, BVH_GROW) |
           quad_test(fr, n + sizeof(bvh_f4), t_lo, t_hi, tn + 4, BVH_GROW) << 4;
}

/* Media met in the leaves are tested after every surface, against the nearest surface hit:
   a fog that fills the scene is met first, and tested then, along its whole chord, it needs
   the log for two path segments in three (final's fog; one in three when tested last) and
   makes scatter points that the surface the ray finds next replaces. A medium's hit depends
   only on the ray and (t_min, t_max), so the nearest hit is the same in any order. Past
   BVH_MEDIA in one ray they are tested as met, as are transformed ones (their hash is of the
   ray in object space). */
#define BVH_MEDIA 4

/* What a ray's leaf tests update: the nearest hit so far (t_max, and t_hi above it in float
   for the box tests) and the media met (their prims and flights in a media_met), whose test
   waits for the nearest surface. */
struct leaf_run {
    double t_max;
    float t_hi;
    int got, n_media;
    uint64_t ray_hash;
};
struct media_met {
    int32_t prim[BVH_MEDIA];
    struct medium_flight flight[BVH_MEDIA];
};

/* A plain medium met in a leaf: its flight starts now (its latency hides under the traversal);
   finish tests it against the nearest surface. */
static inline __attribute__((always_inline)) void meet_medium(const struct prim *pr, int p, const ray *r,
                                                              struct leaf_run *lr, struct media_met *mm,
                                                              int media_inline)
{
    if (lr->n_media == 0)
        lr->ray_hash = media_inline ? ray_hash_inline(r) : shape_ray_hash(r);
    if (media_inline)
        medium_flight_inline(pr, r, lr->ray_hash, &mm->flight[lr->n_media]);
    else
        shape_medium_flight(pr, r, lr->ray_hash, &mm->flight[lr->n_media]);
    mm->prim[lr->n_media++] = p;
}

/* Prim p's hit h is the nearest so far: the ray and its float bound shrink to it. */
static inline __attribute__((always_inline)) void take_hit(struct leaf_run *lr, struct hit *h, int p,
                                                           float grow)
{
    lr->t_max = h->t;
    lr->t_hi = (float)lr->t_max * grow;
    h->prim = p;
    lr->got = 1;
}

/* What test_leaves reads of its traversal: the scene, the ray and its t_min, whether a medium's
   flight is inline (the tree's) or a call (the one node's), and the float bound's growth after a
   hit (NODE_GROW, BVH_GROW). Passed by value: constants in each inlined copy. */
struct leaf_args {
    const struct scene *sc;
    const ray *r;
    double t_min;
    int media_inline;
    float grow;
};

/* Test prim p, of leaf kind `kind` (bvh_prim_kind), against a.r. */
static inline __attribute__((always_inline)) void
test_prim(struct leaf_args a, int p, int kind, struct hit *h, struct leaf_run *lr, struct media_met *mm)
{
    const struct prim *pr = &a.sc->prims[p];
    int got;
    if (kind == BVH_LEAF_MEDIUM && lr->n_media < BVH_MEDIA) {
        meet_medium(pr, p, a.r, lr, mm, a.media_inline);
        return;
    }
    if (kind == BVH_LEAF_RECT)
        got = hit_rect(pr, a.r, a.t_min, lr->t_max, h);
    else if (kind == BVH_LEAF_SPHERE)
        got = hit_sphere(pr->g.sphere.center, pr->g.sphere.radius, a.r, a.t_min, lr->t_max, h);
    else
        got = shape_hit(pr, a.r, a.t_min, lr->t_max, h);
    if (got)
        take_hit(lr, h, p, a.grow);
}

/* Test the prims of node n's leaf lanes m (entry distances tn) against a.r, as met. */
static inline __attribute__((always_inline)) void test_leaves(struct leaf_args a, const struct bvh_node *n,
                                                              int m, const float *tn, struct hit *h,
                                                              struct leaf_run *lr, struct media_met *mm)
{
    for (; m; m &= m - 1) {
        int c = __builtin_ctz((unsigned)m);
        if (tn[c] > lr->t_hi)
            continue;
        if (n->kind[c] != BVH_LEAF_ANY) /* one prim, dispatched by the node, not the prim's type */
            test_prim(a, n->child[c], n->kind[c], h, lr, mm);
        else
            for (int i = n->child[c]; i < n->child[c] + n->count[c]; i++)
                test_prim(a, a.sc->prim_order[i], bvh_prim_kind(&a.sc->prims[a.sc->prim_order[i]]), h, lr,
                          mm);
    }
}

/* The media met, against the nearest surface hit; whether anything was hit. */
static inline __attribute__((always_inline)) int finish(const struct scene *sc, const ray *r, double t_min,
                                                        struct hit *h, struct leaf_run *lr,
                                                        const struct media_met *mm)
{
    for (int i = 0; i < lr->n_media; i++)
        if (shape_medium_hit(&sc->prims[mm->prim[i]], r, &mm->flight[i], t_min, lr->t_max, h))
            take_hit(lr, h, mm->prim[i], BVH_GROW); /* (t_hi no longer read) */
    return lr->got;
}

/* A scene of one node (at most BVH_WIDTH prims, every lane a leaf): its leaves in one pass,
   without the stack and the interior children's bookkeeping, in a function of its own (bvh.h's
   bvh_hit picks it), so it does not pay bvh_hit_tree's frame and register saves either. */
int bvh_hit_node(const struct scene *sc, const ray *r, double t_min, double t_max, struct hit *h)
{
    struct fray fr;
    fray_init_sse(&fr, r);
    const bvh_f4 t_lo = f4_splat((float)t_min * (1.0f - 0x1.0p-20f));
    struct leaf_run lr = {.t_max = t_max, .t_hi = (float)t_max * NODE_GROW};
    struct media_met mm;
    const struct bvh_node *n = &sc->nodes[0];
    float tn[BVH_WIDTH];
    int hit = node_test(&fr, (const char *)n, n->quads, t_lo, lr.t_hi, tn, NODE_GROW);
    test_leaves((struct leaf_args){sc, r, t_min, 0, NODE_GROW}, n, hit, tn, h, &lr, &mm);
    return finish(sc, r, t_min, h, &lr, &mm);
}

struct bvh_entry {
    int32_t node;
    float t; /* entry distance into the node's box */
};

/* The traversal's state between node visits: the float ray, its box bounds, the leaf tests'
   results and the stack of pushed nodes. */
struct tree_walk {
    struct fray fr;
    bvh_f4 t_lo;
    struct leaf_run lr;
    struct media_met mm;
    int sp;
    struct bvh_entry stack[BVH_STACK];
};

/* Visit node `node`: its leaves, then the next node (its nearest interior child in reach, the
   others pushed farthest first, or the nearest pushed node still in reach); -1 when none is
   left. Inlined twice by bvh_hit_tree, so that the root's visit (every ray's first, over the
   same lanes) has branches of its own for the predictor. */
static inline __attribute__((always_inline)) int visit(const struct scene *sc, const ray *r, double t_min,
                                                       struct hit *h, struct tree_walk *w, int node)
{
    const struct bvh_node *n = &sc->nodes[node];
    float tn[BVH_WIDTH];
    int hit = node_test8(&w->fr, (const char *)n, w->t_lo, w->lr.t_hi, tn);
    /* Leaf children first, as met: their hits shorten the ray for the other children. */
    test_leaves((struct leaf_args){sc, r, t_min, 1, BVH_GROW}, n, hit & n->leaves, tn, h, &w->lr, &w->mm);
    /* Then the nearest interior child next, the others pushed farthest first; one alone (a
       third of final's visits, half have none) goes next without the pushes' bookkeeping. */
    int inner = hit & ~n->leaves;
    if (__builtin_expect((inner & (inner - 1)) != 0, 0)) {
        int next = -1;
        float next_t = 0;
        int base = w->sp;
        for (; inner; inner &= inner - 1) {
            int c = __builtin_ctz((unsigned)inner);
            if (tn[c] > w->lr.t_hi)
                continue;
            struct bvh_entry k = {n->child[c], tn[c]};
            if (next < 0) {
                next = k.node, next_t = k.t;
                continue;
            }
            if (k.t < next_t) { /* k is the new nearest: push the old one */
                struct bvh_entry old = {next, next_t};
                next = k.node, next_t = k.t;
                k = old;
            }
            int j = w->sp++;
            while (j > base && w->stack[j - 1].t < k.t) {
                w->stack[j] = w->stack[j - 1];
                j--;
            }
            w->stack[j] = k;
        }
        if (next >= 0)
            return next;
    } else if (inner) {
        int c = __builtin_ctz((unsigned)inner);
        if (tn[c] <= w->lr.t_hi)
            return n->child[c];
    }
    /* Pop the nearest pushed node still in reach of the nearest hit so far. */
    while (w->sp > 0 && w->stack[w->sp - 1].t > w->lr.t_hi)
        w->sp--;
    if (w->sp == 0)
        return -1;
    return w->stack[--w->sp].node;
}

int bvh_hit_tree(const struct scene *sc, const ray *r, double t_min, double t_max, struct hit *h)
{
    struct tree_walk w;
    fray_init(&w.fr, r);
    w.t_lo = f4_splat((float)t_min * (1.0f - 0x1.0p-20f));
    /* t_hi above t_max: rounding never cuts a hit off */
    w.lr = (struct leaf_run){.t_max = t_max, .t_hi = (float)t_max * BVH_GROW};
    w.sp = 0;
    for (int node = visit(sc, r, t_min, h, &w, 0); node >= 0;)
        node = visit(sc, r, t_min, h, &w, node);
    return finish(sc, r, t_min, h, &w.lr, &w.mm);
}
