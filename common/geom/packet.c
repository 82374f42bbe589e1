/* packet: four rays against every prim of a one-node scene at once, in double SIMD lanes (GCC's
   vector extensions: AVX2 where the CPU has it, pairs of SSE2 vectors elsewhere). Each test does
   its scalar test's operations in the same order (hit_rect, hit_sphere, shape.c's hit_box,
   hit_disk and hit_triangle; no FMA contraction), so each lane's t is the scalar t bit for bit;
   a lane keeps a prim's hit when it is nearer than its nearest so far (strict: the first prim
   wins a tie, as in bvh.c's leaf loop, which tests the prims in this order). The hit records are
   made once, for the winners, also in the lanes (a box's by its scalar test). Prims without a
   packet test are tested after, lane by lane, by shape_hit. */
#include "packet.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "base/simd.h"
#include "shape_inline.h"

typedef double d4 __attribute__((vector_size(32)));
typedef int64_t i4 __attribute__((vector_size(32)));
typedef double d2 __attribute__((vector_size(16)));

#define AI inline __attribute__((always_inline))

enum { PK_RECT_X, PK_RECT_Y, PK_RECT_Z, PK_SPHERE, PK_BOX, PK_DISK, PK_TRIANGLE, PK_OTHER };

/* A prim's constants for its packet test, each in all four lanes: a rect's k, a0, a1, b0, b1; a
   sphere's centre and radius^2; a box's cos_y, sin_y, offset, lo and hi; a disk's centre, normal
   and radius^2; a triangle's v0, e1, e2. */
struct packet_prim {
    d4 v[12];
    int kind, prim, xform;
} __attribute__((aligned(32))); /* also where d4 alone gets less (a build without AVX) */

/* What a winner's record needs (index: the prim's place in the order + 1; 0: no hit): the
   outward normal n, or (p - c) s for a sphere (mask `sphere` all ones); `scalar`: the record is
   its scalar test's. c and s, n and sphere: one 32-byte load each (transposed in the lanes),
   so each pair is contiguous and 32-byte aligned (checked below). */
struct packet_rec {
    double c[3], s, n[3];
    int64_t sphere;
    int prim, scalar;
} __attribute__((aligned(32)));
_Static_assert(offsetof(struct packet_rec, s) == offsetof(struct packet_rec, c) + 3 * sizeof(double) &&
                   offsetof(struct packet_rec, sphere) ==
                       offsetof(struct packet_rec, n) + 3 * sizeof(double) &&
                   offsetof(struct packet_rec, n) % 32 == 0,
               "packet_rec's pairs must be 32-byte rows");

struct packet_scene {
    const struct scene *sc;
    int n, n_other;
    struct packet_prim *prims;
    struct packet_rec *rec;
};

static AI d4 d4_splat(double x)
{
    return (d4){x, x, x, x};
}

/* m ? a : b lane by lane (m all ones or all zeros per lane) */
static AI d4 d4_pick(i4 m, d4 a, d4 b)
{
    return (d4)(((i4)a & m) | ((i4)b & ~m));
}

static AI d4 d4_sqrt(d4 x)
{
#if SIMD_SSE
    d2 lo = __builtin_shufflevector(x, x, 0, 1), hi = __builtin_shufflevector(x, x, 2, 3);
    lo = __builtin_ia32_sqrtpd(lo);
    hi = __builtin_ia32_sqrtpd(hi);
    return __builtin_shufflevector(lo, hi, 0, 1, 2, 3);
#else
    return (d4){sqrt(x[0]), sqrt(x[1]), sqrt(x[2]), sqrt(x[3])};
#endif
}

/* The packet's rays by component, and each lane's nearest hit so far (its prim's place in the
   order; -1: none). */
struct packet {
    d4 o[3], d[3];
    d4 t_min, best_t;
    i4 best_i;
};

static AI void keep(struct packet *pk, i4 m, d4 t, int64_t i)
{
    pk->best_t = d4_pick(m, t, pk->best_t);
    pk->best_i = (pk->best_i & ~m) | ((i4){i, i, i, i} & m);
}

/* hit_rect's test for a rect of normal axis on and in-plane axes oa, ob (constants). */
static AI void rect4(struct packet *pk, const struct packet_prim *e, int64_t i, int on, int oa, int ob)
{
    d4 t = (e->v[0] - pk->o[on]) / pk->d[on];
    i4 m = (t > pk->t_min) & (t < pk->best_t);
    d4 pa = pk->o[oa] + pk->d[oa] * t, pb = pk->o[ob] + pk->d[ob] * t;
    m &= ~((pa < e->v[1]) | (pa > e->v[2]) | (pb < e->v[3]) | (pb > e->v[4]));
    keep(pk, m, t, i);
}

/* hit_sphere's test (sphere_quadratic, then the roots compared as a t). */
static AI void sphere4(struct packet *pk, const struct packet_prim *e, int64_t i)
{
    d4 ocx = pk->o[0] - e->v[0], ocy = pk->o[1] - e->v[1], ocz = pk->o[2] - e->v[2];
    d4 a = pk->d[0] * pk->d[0] + pk->d[1] * pk->d[1] + pk->d[2] * pk->d[2];
    d4 half_b = ocx * pk->d[0] + ocy * pk->d[1] + ocz * pk->d[2];
    d4 cc = (ocx * ocx + ocy * ocy + ocz * ocz) - e->v[3];
    d4 disc = half_b * half_b - a * cc;
    i4 ok = ~((disc < d4_splat(0)) | (a == d4_splat(0)));
    d4 sq = d4_sqrt(disc);
    d4 lo = pk->t_min * a, hi = pk->best_t * a;
    d4 at0 = -half_b - sq, at1 = -half_b + sq;
    i4 m0 = (at0 > lo) & (at0 < hi), m1 = (at1 > lo) & (at1 < hi);
    d4 at = d4_pick(m0, at0, at1);
    keep(pk, ok & (m0 | m1), at / a, i);
}

/* One slab of hit_box (box_slab): planes lo and hi. */
static AI void box_slab4(d4 lo, d4 hi, d4 o, d4 d, d4 *t_near, d4 *t_far)
{
    i4 neg = (i4)d < (i4){0, 0, 0, 0};
    d4 near = d4_pick(neg, hi, lo), far = d4_pick(neg, lo, hi);
    d4 inv = d4_splat(1.0) / d;
    d4 tn = (near - o) * inv, tf = (far - o) * inv;
    *t_near = d4_pick(tn > *t_near, tn, *t_near);
    *t_far = d4_pick(tf < *t_far, tf, *t_far);
}

/* hit_box's test, its rotate_y + translate included. */
static AI void box4(struct packet *pk, const struct packet_prim *e, int64_t i)
{
    d4 o[3] = {pk->o[0], pk->o[1], pk->o[2]}, d[3] = {pk->d[0], pk->d[1], pk->d[2]};
    if (e->xform) {
        const d4 c = e->v[0], s = e->v[1];
        d4 wx = pk->o[0] - e->v[2], wy = pk->o[1] - e->v[3], wz = pk->o[2] - e->v[4];
        o[0] = c * wx - s * wz, o[1] = wy, o[2] = s * wx + c * wz;
        d[0] = c * pk->d[0] - s * pk->d[2], d[2] = s * pk->d[0] + c * pk->d[2];
    }
    d4 t_near = d4_splat(-INFINITY), t_far = d4_splat(INFINITY);
    box_slab4(e->v[5], e->v[8], o[0], d[0], &t_near, &t_far);
    box_slab4(e->v[6], e->v[9], o[1], d[1], &t_near, &t_far);
    box_slab4(e->v[7], e->v[10], o[2], d[2], &t_near, &t_far);
    i4 entry = (t_near > pk->t_min) & (t_near < pk->best_t);
    i4 leave = (t_far > pk->t_min) & (t_far < pk->best_t);
    i4 m = ~(t_near > t_far) & (entry | leave);
    keep(pk, m, d4_pick(entry, t_near, t_far), i);
}

/* hit_disk's test. */
static AI void disk4(struct packet *pk, const struct packet_prim *e, int64_t i)
{
    const d4 *v = e->v;
    d4 dn = pk->d[0] * v[3] + pk->d[1] * v[4] + pk->d[2] * v[5];
    d4 t = ((v[0] - pk->o[0]) * v[3] + (v[1] - pk->o[1]) * v[4] + (v[2] - pk->o[2]) * v[5]) / dn;
    i4 m = ~(dn == d4_splat(0)) & (t > pk->t_min) & (t < pk->best_t);
    d4 qx = pk->o[0] + pk->d[0] * t - v[0], qy = pk->o[1] + pk->d[1] * t - v[1],
       qz = pk->o[2] + pk->d[2] * t - v[2];
    m &= ~(qx * qx + qy * qy + qz * qz > v[6]);
    keep(pk, m, t, i);
}

/* hit_triangle's test (Moller & Trumbore). */
static AI void triangle4(struct packet *pk, const struct packet_prim *e, int64_t i)
{
    const d4 *v = e->v, *d = pk->d;
    const d4 e1x = v[3], e1y = v[4], e1z = v[5], e2x = v[6], e2y = v[7], e2z = v[8];
    d4 px = d[1] * e2z - d[2] * e2y, py = d[2] * e2x - d[0] * e2z, pz = d[0] * e2y - d[1] * e2x;
    d4 det = e1x * px + e1y * py + e1z * pz;
    d4 inv = d4_splat(1.0) / det;
    d4 tx = pk->o[0] - v[0], ty = pk->o[1] - v[1], tz = pk->o[2] - v[2];
    d4 u = (tx * px + ty * py + tz * pz) * inv;
    d4 qx = ty * e1z - tz * e1y, qy = tz * e1x - tx * e1z, qz = tx * e1y - ty * e1x;
    d4 w = (d[0] * qx + d[1] * qy + d[2] * qz) * inv;
    d4 t = (e2x * qx + e2y * qy + e2z * qz) * inv;
    i4 m = ~((det == d4_splat(0)) | (u < d4_splat(0)) | (u > d4_splat(1)) | (w < d4_splat(0)) |
             (u + w > d4_splat(1)));
    keep(pk, m & (t > pk->t_min) & (t < pk->best_t), t, i);
}

int packet_usable(const struct scene *sc)
{
    if (sc->n_nodes != 1)
        return 0;
    for (int i = 0; i < sc->n_prims; i++) {
        const struct prim *p = &sc->prims[i];
        if (p->type != PRIM_BOX && (p->has_xform || (p->type != PRIM_RECT && p->type != PRIM_SPHERE &&
                                                     p->type != PRIM_DISK && p->type != PRIM_TRIANGLE)))
            return 0;
    }
    return 1;
}

static void add_prim(struct packet_scene *ps, int p)
{
    const struct prim *pr = &ps->sc->prims[p];
    const int k = ps->n++;
    struct packet_prim *e = &ps->prims[k];
    struct packet_rec *rc = &ps->rec[k + 1];
    double v[12] = {0};
    e->prim = rc->prim = p;
    e->xform = pr->has_xform;
    if (pr->type == PRIM_RECT && !pr->has_xform) {
        e->kind = PK_RECT_X + pr->g.rect.axis;
        v[0] = pr->g.rect.k, v[1] = pr->g.rect.a0, v[2] = pr->g.rect.a1;
        v[3] = pr->g.rect.b0, v[4] = pr->g.rect.b1;
        vec3 n = pr->flip ? v3_neg(pr->g.rect.n) : pr->g.rect.n; /* hit_rect's outward normal */
        rc->n[0] = n.x, rc->n[1] = n.y, rc->n[2] = n.z;
    } else if (pr->type == PRIM_SPHERE && !pr->has_xform) {
        e->kind = PK_SPHERE;
        vec3 c = pr->g.sphere.center;
        double rad = pr->g.sphere.radius;
        v[0] = c.x, v[1] = c.y, v[2] = c.z, v[3] = rad * rad;
        rc->c[0] = c.x, rc->c[1] = c.y, rc->c[2] = c.z, rc->s = 1.0 / rad;
        rc->sphere = -1;
    } else if (pr->type == PRIM_DISK && !pr->has_xform) {
        e->kind = PK_DISK;
        vec3 c = pr->g.disk.center, n = pr->g.disk.normal;
        v[0] = c.x, v[1] = c.y, v[2] = c.z, v[3] = n.x, v[4] = n.y, v[5] = n.z;
        v[6] = pr->g.disk.radius * pr->g.disk.radius;
        rc->n[0] = n.x, rc->n[1] = n.y, rc->n[2] = n.z;
    } else if (pr->type == PRIM_TRIANGLE && !pr->has_xform) {
        e->kind = PK_TRIANGLE;
        vec3 v0 = pr->g.tri.v0, e1 = pr->g.tri.e1, e2 = pr->g.tri.e2, n = pr->g.tri.normal;
        v[0] = v0.x, v[1] = v0.y, v[2] = v0.z, v[3] = e1.x, v[4] = e1.y, v[5] = e1.z;
        v[6] = e2.x, v[7] = e2.y, v[8] = e2.z;
        rc->n[0] = n.x, rc->n[1] = n.y, rc->n[2] = n.z;
    } else if (pr->type == PRIM_BOX) {
        e->kind = PK_BOX;
        v[0] = pr->cos_y, v[1] = pr->sin_y, v[2] = pr->offset.x, v[3] = pr->offset.y, v[4] = pr->offset.z;
        v[5] = pr->g.box.lo.x, v[6] = pr->g.box.lo.y, v[7] = pr->g.box.lo.z;
        v[8] = pr->g.box.hi.x, v[9] = pr->g.box.hi.y, v[10] = pr->g.box.hi.z;
        rc->scalar = 1;
    } else {
        e->kind = PK_OTHER;
        rc->scalar = 1;
        ps->n_other++;
    }
    for (int j = 0; j < 12; j++)
        e->v[j] = d4_splat(v[j]);
}

struct packet_scene *packet_scene_new(const struct scene *sc)
{
    struct packet_scene *ps = calloc(1, sizeof *ps);
    if (!ps)
        return NULL;
    ps->sc = sc;
    ps->prims = aligned_alloc(32, ((size_t)sc->n_prims + 1) * sizeof *ps->prims);
    ps->rec = aligned_alloc(32, ((size_t)sc->n_prims + 1) * sizeof *ps->rec);
    if (!ps->prims || !ps->rec) {
        packet_scene_free(ps);
        return NULL;
    }
    memset(ps->rec, 0, ((size_t)sc->n_prims + 1) * sizeof *ps->rec);
    const struct bvh_node *n = &sc->nodes[0];
    for (int m = n->leaves; m; m &= m - 1) {
        int c = __builtin_ctz((unsigned)m);
        if (n->kind[c] != BVH_LEAF_ANY)
            add_prim(ps, n->child[c]);
        else
            for (int i = n->child[c]; i < n->child[c] + n->count[c]; i++)
                add_prim(ps, sc->prim_order[i]);
    }
    return ps;
}

void packet_scene_free(struct packet_scene *ps)
{
    if (!ps)
        return;
    free(ps->prims);
    free(ps->rec);
    free(ps);
}

/* The other prims, lane by lane, after the packet's: a hit nearer than the lane's nearest wins,
   and so does one as near from a prim earlier in the order (the tie bvh.c's order resolves
   for it). */
static __attribute__((noinline)) void test_others(const struct packet_scene *ps,
                                                  const ray *const r[PACKET_LANES], double t_min,
                                                  double best_t[PACKET_LANES], int64_t best_i[PACKET_LANES])
{
    for (int k = 0; k < ps->n; k++) {
        if (ps->prims[k].kind != PK_OTHER)
            continue;
        const struct prim *pr = &ps->sc->prims[ps->prims[k].prim];
        for (int i = 0; i < PACKET_LANES; i++) {
            struct hit h;
            if (!shape_hit(pr, r[i], t_min, nextafter(best_t[i], INFINITY), &h))
                continue;
            if (h.t < best_t[i] || (h.t == best_t[i] && best_i[i] > k)) {
                best_t[i] = h.t;
                best_i[i] = k;
            }
        }
    }
}

/* The records of lanes `lanes` by their prims' scalar tests (boxes and other prims). */
static __attribute__((noinline)) void record_scalar(const struct packet_scene *ps,
                                                    const ray *const r[PACKET_LANES], int lanes, double t_min,
                                                    double t_max, struct packet_hits *ph)
{
    for (; lanes; lanes &= lanes - 1) {
        int i = __builtin_ctz((unsigned)lanes);
        struct hit *h = &ph->h[i];
        const int prim = h->prim;
        shape_hit(&ps->sc->prims[prim], r[i], t_min, t_max, h);
        h->prim = prim;
        h->u = h->v = 0;
    }
}

/* The double at byte offset off of each of the four structs p[i], as a vector. */
static AI d4 gather4(const void *const p[PACKET_LANES], size_t off)
{
    double x0, x1, x2, x3;
    memcpy(&x0, (const char *)p[0] + off, sizeof x0);
    memcpy(&x1, (const char *)p[1] + off, sizeof x1);
    memcpy(&x2, (const char *)p[2] + off, sizeof x2);
    memcpy(&x3, (const char *)p[3] + off, sizeof x3);
    return (d4){x0, x1, x2, x3};
}

/* The 32 bytes at offset off of each lane's record (32-byte aligned there) as four columns c[0..3].
   Copied, not read through a cast pointer: a row may hold an int64_t (n's sphere mask). */
static AI void transpose4(const struct packet_rec *const rc[PACKET_LANES], size_t off, d4 c[4])
{
    d4 a0, a1, a2, a3;
    memcpy(&a0, (const char *)rc[0] + off, sizeof a0);
    memcpy(&a1, (const char *)rc[1] + off, sizeof a1);
    memcpy(&a2, (const char *)rc[2] + off, sizeof a2);
    memcpy(&a3, (const char *)rc[3] + off, sizeof a3);
    const d4 lo01 = __builtin_shufflevector(a0, a1, 0, 4, 2, 6),
             hi01 = __builtin_shufflevector(a0, a1, 1, 5, 3, 7);
    const d4 lo23 = __builtin_shufflevector(a2, a3, 0, 4, 2, 6),
             hi23 = __builtin_shufflevector(a2, a3, 1, 5, 3, 7);
    c[0] = __builtin_shufflevector(lo01, lo23, 0, 1, 4, 5);
    c[1] = __builtin_shufflevector(hi01, hi23, 0, 1, 4, 5);
    c[2] = __builtin_shufflevector(lo01, lo23, 2, 3, 6, 7);
    c[3] = __builtin_shufflevector(hi01, hi23, 2, 3, 6, 7);
}

/* One copy for AVX2, one for the baseline, picked when the program loads (x86-64 only; a test
   builds the baseline alone by defining PACKET_CLONES empty). */
#if !defined(PACKET_CLONES) && SIMD_SSE && defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PACKET_CLONES __attribute__((target_clones("avx2", "default")))
#elif !defined(PACKET_CLONES)
#define PACKET_CLONES
#endif

PACKET_CLONES int packet_hit(const struct packet_scene *ps, const ray *const r[PACKET_LANES], double t_min,
                             double t_max, struct packet_hits *ph)
{
    struct packet pk;
    const void *const rv[PACKET_LANES] = {r[0], r[1], r[2], r[3]};
    pk.o[0] = gather4(rv, offsetof(ray, orig.x)), pk.o[1] = gather4(rv, offsetof(ray, orig.y));
    pk.o[2] = gather4(rv, offsetof(ray, orig.z)), pk.d[0] = gather4(rv, offsetof(ray, dir.x));
    pk.d[1] = gather4(rv, offsetof(ray, dir.y)), pk.d[2] = gather4(rv, offsetof(ray, dir.z));
    pk.t_min = d4_splat(t_min);
    pk.best_t = d4_splat(t_max);
    pk.best_i = (i4){-1, -1, -1, -1};
    for (int k = 0; k < ps->n; k++) {
        const struct packet_prim *e = &ps->prims[k];
        if (e->kind == PK_RECT_X)
            rect4(&pk, e, k, 0, 1, 2);
        else if (e->kind == PK_RECT_Y)
            rect4(&pk, e, k, 1, 0, 2);
        else if (e->kind == PK_RECT_Z)
            rect4(&pk, e, k, 2, 0, 1);
        else if (e->kind == PK_SPHERE)
            sphere4(&pk, e, k);
        else if (e->kind == PK_BOX)
            box4(&pk, e, k);
        else if (e->kind == PK_DISK)
            disk4(&pk, e, k);
        else if (e->kind == PK_TRIANGLE)
            triangle4(&pk, e, k);
    }
    double best_t[PACKET_LANES];
    int64_t best_i[PACKET_LANES];
    memcpy(best_t, &pk.best_t, sizeof best_t);
    memcpy(best_i, &pk.best_i, sizeof best_i);
    if (ps->n_other) {
        test_others(ps, r, t_min, best_t, best_i);
        memcpy(&pk.best_t, best_t, sizeof best_t);
    }
    /* The records: p on the ray, the outward normal n or (p - c) s, then set_face's. */
    const struct packet_rec *rc[PACKET_LANES];
    int got = 0, scalar = 0;
    for (int i = 0; i < PACKET_LANES; i++) {
        rc[i] = &ps->rec[best_i[i] + 1];
        got |= (best_i[i] >= 0) << i;
        scalar |= rc[i]->scalar << i;
        ph->h[i].prim = rc[i]->prim;
    }
    d4 c[4], nm[4];
    transpose4(rc, offsetof(struct packet_rec, c), c);
    transpose4(rc, offsetof(struct packet_rec, n), nm);
    const d4 t = pk.best_t;
    const d4 px = pk.o[0] + pk.d[0] * t, py = pk.o[1] + pk.d[1] * t, pz = pk.o[2] + pk.d[2] * t;
    const i4 sphere = (i4)nm[3];
    const d4 ux = d4_pick(sphere, (px - c[0]) * c[3], nm[0]);
    const d4 uy = d4_pick(sphere, (py - c[1]) * c[3], nm[1]);
    const d4 uz = d4_pick(sphere, (pz - c[2]) * c[3], nm[2]);
    const i4 front = pk.d[0] * ux + pk.d[1] * uy + pk.d[2] * uz < d4_splat(0);
    const i4 flip = ~front & (i4)d4_splat(-0.0);
    const d4 nx = (d4)((i4)ux ^ flip), ny = (d4)((i4)uy ^ flip), nz = (d4)((i4)uz ^ flip);
    for (int i = 0; i < PACKET_LANES; i++) {
        struct hit *h = &ph->h[i];
        h->t = t[i];
        h->p = v3(px[i], py[i], pz[i]);
        h->n = v3(nx[i], ny[i], nz[i]);
        h->u = h->v = 0;
        h->front = front[i] != 0;
    }
    if (scalar & got)
        record_scalar(ps, r, scalar & got, t_min, t_max, ph);
    return got;
}
