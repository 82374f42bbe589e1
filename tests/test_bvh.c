/* Tests for the BVH: its nearest hit equals a linear scan's, also for rays that graze box
   corners and edges, run along faces or start far away (the float slab test's hard cases). */
#include <float.h>
#include <stdlib.h>

#include "geom/bvh.h"
#include "box_point.h"
#include "check.h"
#include "base/rng.h"
#include "scenefile/scene_load.h"
#include "geom/shape.h"

/* Nearest hit by testing every primitive. */
static int linear_hit(const struct scene *sc, const ray *r, struct hit *h)
{
    double t_max = DBL_MAX;
    int got = 0;
    for (int i = 0; i < sc->n_prims; i++)
        if (shape_hit(&sc->prims[i], r, HIT_EPS, t_max, h)) {
            t_max = h->t;
            h->prim = i;
            got = 1;
        }
    return got;
}

/* 1 when bvh_hit and the linear scan agree on r (hit or not, and the distance). */
static int agrees(const struct scene *sc, const ray *r, int *hits)
{
    struct hit a, b;
    int ga = bvh_hit(sc, r, HIT_EPS, DBL_MAX, &a), gb = linear_hit(sc, r, &b);
    *hits += ga;
    if (ga != gb)
        return 0;
    return !ga || fabs(a.t - b.t) <= 1e-9 * (1 + fabs(b.t));
}

/* Every leaf lane's kind says what its prims are (bvh_hit dispatches on it without looking):
   one untransformed rect, sphere or medium, one prim for shape_hit, or anything (BVH_LEAF_ANY). */
static int kinds_ok(const struct scene *sc)
{
    int ok = 1;
    for (int i = 0; i < sc->n_nodes; i++) {
        const struct bvh_node *n = &sc->nodes[i];
        for (int c = 0; c < BVH_WIDTH; c++) {
            if (!(n->leaves >> c & 1)) {
                ok &= n->kind[c] == BVH_LEAF_ANY;
                continue;
            }
            int first = n->kind[c] == BVH_LEAF_ANY ? sc->prim_order[n->child[c]] : n->child[c];
            const struct prim *p = &sc->prims[first];
            int one = n->count[c] == 1, plain = one && !p->has_xform;
            switch (n->kind[c]) {
            case BVH_LEAF_RECT:
                ok &= plain && p->type == PRIM_RECT;
                break;
            case BVH_LEAF_SPHERE:
                ok &= plain && p->type == PRIM_SPHERE;
                break;
            case BVH_LEAF_MEDIUM:
                ok &= plain && p->type == PRIM_MEDIUM;
                break;
            case BVH_LEAF_SHAPE:
                ok &= one && (p->has_xform ||
                              (p->type != PRIM_RECT && p->type != PRIM_SPHERE && p->type != PRIM_MEDIUM));
                break;
            default:
                ok &= n->kind[c] == BVH_LEAF_ANY;
            }
        }
    }
    return ok;
}

/* A tree's nodes (more than one: bvh_hit_tree) use at most two quads, and bvh_hit_tree tests
   both: every lane past the node's quads is empty (never hit) and no leaf. */
static int lanes_ok(const struct scene *sc)
{
    int ok = 1;
    for (int i = 0; sc->n_nodes > 1 && i < sc->n_nodes; i++) {
        const struct bvh_node *n = &sc->nodes[i];
        ok &= n->quads >= 1 && n->quads <= 2;
        for (int c = 4 * n->quads; c < BVH_WIDTH; c++) {
            ok &= !(n->leaves >> c & 1) && n->count[c] == 0;
            for (int a = 0; a < 3; a++)
                ok &= n->lo[a][c] == INFINITY && n->hi[a][c] == -INFINITY;
        }
    }
    return ok;
}

/* Rays toward 27 points of every stride-th prim's box, from inside the scene and from far_origin. */
static void test_scene(const char *path, vec3 far_origin, int stride)
{
    struct scene_file sf = {0};
    struct err e;
    CHECK(scene_load(path, &sf, &e) == 0);
    if (!sf.scene)
        return;
    const struct scene *sc = sf.scene;
    CHECK(kinds_ok(sc));
    CHECK(lanes_ok(sc));
    vec3 lo = v3(DBL_MAX, DBL_MAX, DBL_MAX), hi = v3(-DBL_MAX, -DBL_MAX, -DBL_MAX);
    for (int i = 0; i < sc->n_prims; i++) {
        vec3 l, h;
        shape_bounds(&sc->prims[i], &l, &h);
        if (h.x - l.x > 2000) /* the final scene's fog: keep origins near the geometry */
            continue;
        lo = v3_min(lo, l), hi = v3_max(hi, h);
    }
    struct rng r;
    rng_seed(&r, 3, 3);
    int ok = 1, hits = 0, rays = 0;
    for (int i = 0; i < sc->n_prims; i += stride) {
        vec3 pl, ph;
        shape_bounds(&sc->prims[i], &pl, &ph);
        for (int k = 0; k < 27; k++) {
            vec3 target = box_point(pl, ph, k);
            vec3 inside = v3(lo.x + rng_uniform(&r) * (hi.x - lo.x), lo.y + rng_uniform(&r) * (hi.y - lo.y),
                             lo.z + rng_uniform(&r) * (hi.z - lo.z));
            vec3 origins[2] = {inside, far_origin};
            for (int o = 0; o < 2; o++) {
                ray q = {origins[o], v3_sub(target, origins[o]), rng_uniform(&r)};
                ok &= agrees(sc, &q, &hits);
                /* the same ray along an axis from the target's plane: zero direction components */
                ray axis = {target, v3(k % 3 == 0 ? 1 : 0, k % 3 == 1 ? -1 : 0, k % 3 == 2 ? 1 : 0), 0.5};
                ok &= agrees(sc, &axis, &hits);
                /* and with negative zeros (as negating a direction makes them) */
                ray neg = {v3_add(target, v3(0, 0.5, 0)), v3(-0.0, -1, -0.0), 0.5};
                ok &= agrees(sc, &neg, &hits);
                rays += 3;
            }
        }
    }
    fprintf(stderr, "%s: %d rays, %d hits\n", path, rays, hits);
    CHECK(ok);
    CHECK(hits > rays / 4);
    scene_file_free(&sf);
}

/* A scene of one prim (the root holds a single leaf) and an empty scene. */
static void test_small(void)
{
    struct scene *sc = scene_new();
    struct err e;
    CHECK(scene_finish(sc, &e) == 0);
    ray q = {v3(0, 0, -5), v3(0, 0, 1), 0};
    struct hit h;
    CHECK(!bvh_hit(sc, &q, HIT_EPS, DBL_MAX, &h));
    struct material m = {.type = MAT_LAMBERTIAN, .albedo = v3(0.5, 0.5, 0.5), .texture = -1};
    scene_add_material(sc, &m);
    struct prim p = {.type = PRIM_SPHERE, .material = 0};
    p.g.sphere.center = v3(0, 0, 0);
    p.g.sphere.radius = 1;
    scene_add_prim(sc, &p);
    CHECK(scene_finish(sc, &e) == 0);
    CHECK(bvh_hit(sc, &q, HIT_EPS, DBL_MAX, &h) && h.prim == 0);
    CHECK_NEAR(h.t, 4, 1e-12);
    CHECK(!bvh_hit(sc, &q, HIT_EPS, 3.9, &h));
    ray miss = {v3(0, 1.0001, -5), v3(0, 0, 1), 0};
    CHECK(!bvh_hit(sc, &miss, HIT_EPS, DBL_MAX, &h));
    scene_free(sc);
}

/* 3000 concentric spheres (no centroid split exists) and 3000 in a row of growing size (the
   SAH may peel them off one by one): the tree stays within its depth, leaves stay small, and
   hits agree with a linear scan. */
static void test_degenerate(void)
{
    for (int kind = 0; kind < 2; kind++) {
        struct scene *sc = scene_new();
        struct material m = {.type = MAT_LAMBERTIAN, .albedo = v3(0.5, 0.5, 0.5), .texture = -1};
        scene_add_material(sc, &m);
        for (int i = 0; i < 3000; i++) {
            struct prim p = {.type = PRIM_SPHERE, .material = 0};
            p.g.sphere.center = kind ? v3(pow(1.003, i), 0, 0) : v3(0, 0, 0);
            p.g.sphere.radius = kind ? 0.001 * pow(1.003, i) : 1 + i;
            scene_add_prim(sc, &p);
        }
        struct err e;
        CHECK(scene_finish(sc, &e) == 0);
        int small = 1;
        for (int i = 0; i < sc->n_nodes; i++)
            for (int c = 0; c < BVH_WIDTH; c++)
                small &= sc->nodes[i].count[c] <= 4;
        CHECK(small);
        struct rng r;
        rng_seed(&r, 8, 8);
        int ok = 1, hits = 0;
        for (int k = 0; k < 500; k++) {
            ray q = {v3(-5000 + 10000 * rng_uniform(&r), 2 + rng_uniform(&r), -5000),
                     v3(rng_uniform(&r) - 0.5, -0.001 * rng_uniform(&r), 1), 0};
            ok &= agrees(sc, &q, &hits);
        }
        CHECK(ok);
        CHECK(hits > 10);
        scene_free(sc);
    }
}

/* Transformed spheres that keep their transform (media: shape_bake leaves them), whose boxes
   bvh_build makes centre +- radius: rays along an axis that pass just inside and just outside each
   sphere's extreme point along another axis (where the box is tight) agree with a linear scan. The
   media are dense enough that any chord scatters. */
static void test_transformed_spheres(void)
{
    struct scene *sc = scene_new();
    struct material m = {.type = MAT_ISOTROPIC, .albedo = v3(0.5, 0.5, 0.5), .texture = -1};
    scene_add_material(sc, &m);
    struct rng r;
    rng_seed(&r, 5, 5);
    for (int i = 0; i < 200; i++) {
        struct prim p = {.type = PRIM_MEDIUM, .material = 0, .has_xform = 1};
        double deg = 360 * rng_uniform(&r);
        p.cos_y = cos(deg * PI / 180), p.sin_y = sin(deg * PI / 180);
        p.offset = v3(300 * rng_uniform(&r), 300 * rng_uniform(&r), 300 * rng_uniform(&r));
        p.g.medium.center = v3(100 * rng_uniform(&r), 100 * rng_uniform(&r), 100 * rng_uniform(&r));
        p.g.medium.radius = 1 + 10 * rng_uniform(&r);
        p.g.medium.neg_inv_density = -1e-12;
        scene_add_prim(sc, &p);
    }
    struct err e;
    CHECK(scene_finish(sc, &e) == 0);
    CHECK(sc->prims[0].has_xform);
    int ok = 1, hits = 0, rays = 0;
    for (int i = 0; i < sc->n_prims; i++) {
        const struct prim *p = &sc->prims[i];
        vec3 c = p->g.medium.center;
        double w[3] = {p->cos_y * c.x + p->sin_y * c.z + p->offset.x, c.y + p->offset.y,
                       -p->sin_y * c.x + p->cos_y * c.z + p->offset.z};
        for (int a = 0; a < 3; a++)           /* the extreme point along axis a */
            for (int b = 0; b < 3; b++)       /* the ray along axis b */
                for (int k = 0; k < 4; k++) { /* low or high side, just inside or just outside */
                    if (a == b)
                        continue;
                    double t[3] = {w[0], w[1], w[2]}, d[3] = {0, 0, 0};
                    t[a] += (k & 1 ? 1 : -1) * p->g.medium.radius * (k & 2 ? 1 + 1e-9 : 1 - 1e-9);
                    d[b] = 1;
                    t[b] -= 1000;
                    ray q = {v3(t[0], t[1], t[2]), v3(d[0], d[1], d[2]), 0.5};
                    ok &= agrees(sc, &q, &hits);
                    rays++;
                }
    }
    CHECK(ok);
    CHECK(hits > rays / 4);
    scene_free(sc);
}

/* A scene of at most BVH_WIDTH prims is one node, which bvh_hit tests without its stack:
   spheres, rects, a box, a plain medium (tested after the surfaces) and a transformed one
   (tested as met), hit from random origins in random directions, agree with a linear scan.
   With 6 spheres the node has four quads in use; with 0 or 3, three. */
static void test_one_node(int n_spheres)
{
    struct scene *sc = scene_new();
    struct material m = {.type = MAT_LAMBERTIAN, .albedo = v3(0.5, 0.5, 0.5), .texture = -1};
    scene_add_material(sc, &m);
    struct rng r;
    rng_seed(&r, 6, 6);
    for (int i = 0; i < n_spheres; i++) {
        struct prim p = {.type = PRIM_SPHERE, .material = 0};
        p.g.sphere.center = v3(10 * rng_uniform(&r), 10 * rng_uniform(&r), 10 * rng_uniform(&r));
        p.g.sphere.radius = 0.5 + rng_uniform(&r);
        scene_add_prim(sc, &p);
    }
    for (int i = 0; i < 6; i++) {
        struct prim p = {.type = PRIM_RECT, .material = 0, .flip = i & 1};
        p.g.rect.axis = i % 3;
        p.g.rect.a0 = 10 * rng_uniform(&r), p.g.rect.a1 = p.g.rect.a0 + 1 + 3 * rng_uniform(&r);
        p.g.rect.b0 = 10 * rng_uniform(&r), p.g.rect.b1 = p.g.rect.b0 + 1 + 3 * rng_uniform(&r);
        p.g.rect.k = 10 * rng_uniform(&r);
        scene_add_prim(sc, &p);
    }
    struct prim b = {.type = PRIM_BOX, .material = 0};
    b.g.box.lo = v3(4, 4, 4), b.g.box.hi = v3(6, 5, 7);
    scene_add_prim(sc, &b);
    for (int i = 0; i < 2; i++) {
        struct prim p = {.type = PRIM_MEDIUM, .material = 0, .has_xform = i, .cos_y = 1};
        p.g.medium.center = v3(5, 5, 5);
        p.g.medium.radius = i ? 2 : 20;
        p.g.medium.neg_inv_density = i ? -0.5 : -30;
        scene_add_prim(sc, &p);
    }
    struct err e;
    CHECK(scene_finish(sc, &e) == 0);
    CHECK(sc->n_prims <= BVH_WIDTH && sc->n_nodes == 1);
    CHECK(sc->nodes[0].quads == (sc->n_prims + 3) / 4);
    CHECK(kinds_ok(sc));
    int ok = 1, hits = 0, fog = 0;
    for (int k = 0; k < 20000; k++) {
        ray q = {v3(-2 + 14 * rng_uniform(&r), -2 + 14 * rng_uniform(&r), -2 + 14 * rng_uniform(&r)),
                 v3(rng_uniform(&r) - 0.5, rng_uniform(&r) - 0.5, rng_uniform(&r) - 0.5), 0};
        struct hit a, c;
        int ga = bvh_hit(sc, &q, HIT_EPS, DBL_MAX, &a), gc = linear_hit(sc, &q, &c);
        hits += ga;
        fog += ga && a.prim == sc->n_prims - 2;
        ok &= ga == gc && (!ga || (a.t == c.t && a.prim == c.prim));
    }
    CHECK(ok);
    /* the plain medium holds every origin; about half the rays scatter in it */
    CHECK(fog > 5000 && hits - fog > (n_spheres == 6 ? 1500 : 500)); /* 8192 and 2308 with 6 */
    scene_free(sc);
}

/* A one-node scene far from the world's origin (coordinates near 2^20, where a float's ulp is
   1/8): rays from a unit or so away toward the corners, edges and faces of each prim's box hit
   what a linear scan hits. The float slab test's origins are rounded there by far more than the
   traversal's margin on t, which only the shifted origins cover. */
static void test_one_node_far(void)
{
    struct scene *sc = scene_new();
    struct material m = {.type = MAT_LAMBERTIAN, .albedo = v3(0.5, 0.5, 0.5), .texture = -1};
    scene_add_material(sc, &m);
    const double c = 1048575.25; /* just below 2^20 */
    for (int i = 0; i < 6; i++) {
        struct prim p = {.type = PRIM_RECT, .material = 0, .flip = i & 1};
        p.g.rect.axis = i % 3;
        p.g.rect.a0 = c - 1.5 + 0.25 * i, p.g.rect.a1 = p.g.rect.a0 + 1.75;
        p.g.rect.b0 = c - 1 - 0.125 * i, p.g.rect.b1 = p.g.rect.b0 + 2.5;
        p.g.rect.k = c + (i < 3 ? -1.25 : 1.5);
        scene_add_prim(sc, &p);
    }
    for (int i = 0; i < 2; i++) {
        struct prim p = {.type = PRIM_SPHERE, .material = 0};
        p.g.sphere.center = v3(c + i, c - i, c + 0.5);
        p.g.sphere.radius = 0.375;
        scene_add_prim(sc, &p);
    }
    struct err e;
    CHECK(scene_finish(sc, &e) == 0);
    CHECK(sc->n_nodes == 1);
    struct rng r;
    rng_seed(&r, 9, 9);
    int ok = 1, hits = 0;
    for (int k = 0; k < 20000; k++) {
        vec3 pl, ph;
        shape_bounds(&sc->prims[k % sc->n_prims], &pl, &ph);
        vec3 target = box_point(pl, ph, k / sc->n_prims % 27);
        vec3 o =
            v3_add(target, v3(4 * rng_uniform(&r) - 2, 4 * rng_uniform(&r) - 2, 4 * rng_uniform(&r) - 2));
        ray q = {o, v3_sub(target, o), 0};
        struct hit a, b;
        int ga = bvh_hit(sc, &q, HIT_EPS, DBL_MAX, &a), gb = linear_hit(sc, &q, &b);
        hits += ga;
        ok &= ga == gb && (!ga || (a.t == b.t && a.prim == b.prim));
    }
    CHECK(ok);
    CHECK(hits > 10000);
    scene_free(sc);
}

int main(void)
{
    test_one_node(6);
    test_one_node(3);
    test_one_node(0);
    test_one_node_far();
    test_transformed_spheres();
    test_small();
    test_degenerate();
    test_scene("scenes/cornell-book3.yaml", v3(278, 278, -800), 1);
    test_scene("scenes/cornell.yaml", v3(278, 278, -800), 1);
    test_scene("scenes/checker.yaml", v3(13, 2, 3), 1);
    test_scene("scenes/final.yaml", v3(478, 278, -600), 17);
    return check_report("test_bvh");
}
