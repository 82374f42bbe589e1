/* Tests for shape_bake: a prim whose rotate_y + translate is folded into its world-space geometry
   hits every ray where the transformed prim does (t, point, normal, side within 1e-9 relative),
   its bounds hold its hits, and what cannot be folded is left alone. */
#include <float.h>
#include <string.h>

#include "check.h"
#include "base/rng.h"
#include "geom/scene.h"
#include "geom/shape.h"

#define RAYS 20000

static void set_xform(struct prim *p, double deg, vec3 offset)
{
    p->has_xform = 1;
    p->cos_y = cos(deg * PI / 180);
    p->sin_y = sin(deg * PI / 180);
    p->offset = offset;
}

static double urange(struct rng *g, double lo, double hi)
{
    return lo + (hi - lo) * rng_uniform(g);
}

static vec3 upoint(struct rng *g, vec3 c, double half)
{
    return v3(urange(g, c.x - half, c.x + half), urange(g, c.y - half, c.y + half),
              urange(g, c.z - half, c.z + half));
}

static int near_rel(double a, double b, double scale)
{
    return fabs(a - b) <= 1e-9 * (fabs(b) > scale ? fabs(b) : scale);
}

/* The object-space prim p under a few transforms: shape_bake folds each, and for random rays
   aimed near it the baked prim's hit equals the transformed one's; hits lie in the baked
   bounds. */
static const double any_turns[5] = {15, -18, 70, 123.4, -200};
static const double quarter_turns[5] = {90, -90, 180, 0, 630};

static void check_fold(const struct prim *p, const char *what, const double angles[5])
{
    static const vec3 offsets[] = {
        {-100, 270, 395}, {160, 230, 80}, {0, 0, 0}, {3.5, -2, 1e3}, {-7, 1, 0.25}};
    struct rng g;
    rng_seed(&g, 11, (uint64_t)p->type);
    int same_hit = 1, same_t = 1, same_p = 1, same_n = 1, same_front = 1, inside = 1, same_uv = 1;
    int hits = 0, misses = 0;
    for (int k = 0; k < 5; k++) {
        struct prim x = *p, b;
        set_xform(&x, angles[k], offsets[k]);
        shape_prepare(&x);
        b = x;
        CHECK(shape_bake(&b, 0) == 1 && !b.has_xform);
        CHECK(shape_area(&b) == shape_area(&x));
        vec3 lo, hi, xlo, xhi;
        shape_bounds(&b, &lo, &hi);
        shape_bounds(&x, &xlo, &xhi);
        vec3 c = v3_scale(v3_add(xlo, xhi), 0.5);
        double size = v3_len(v3_sub(xhi, xlo)), scale = v3_len(c) + size;
        for (int i = 0; i < RAYS; i++) {
            vec3 o = upoint(&g, c, 3 * size), target = upoint(&g, c, 0.3 * size);
            ray r = {o, v3_sub(target, o), rng_uniform(&g)};
            struct hit hx, hb;
            int gx = shape_hit(&x, &r, HIT_EPS, DBL_MAX, &hx), gb = shape_hit(&b, &r, HIT_EPS, DBL_MAX, &hb);
            same_hit &= gx == gb;
            if (!gx || !gb) {
                misses += !gx;
                continue;
            }
            hits++;
            same_t &= near_rel(hb.t, hx.t, 1e-3);
            same_p &= near_rel(hb.p.x, hx.p.x, scale) && near_rel(hb.p.y, hx.p.y, scale) &&
                      near_rel(hb.p.z, hx.p.z, scale);
            same_n &= fabs(hb.n.x - hx.n.x) <= 1e-9 && fabs(hb.n.y - hx.n.y) <= 1e-9 &&
                      fabs(hb.n.z - hx.n.z) <= 1e-9;
            same_front &= hb.front == hx.front;
            const double slack = 1e-9 * scale;
            inside &= hb.p.x >= lo.x - slack && hb.p.x <= hi.x + slack && hb.p.y >= lo.y - slack &&
                      hb.p.y <= hi.y + slack && hb.p.z >= lo.z - slack && hb.p.z <= hi.z + slack;
            if (p->type == PRIM_DISK) { /* its frame turns with it: the same uv */
                shape_uv(&x, &hx);
                shape_uv(&b, &hb);
                same_uv &= fabs(hb.u - hx.u) <= 1e-9 && fabs(hb.v - hx.v) <= 1e-9;
            }
        }
    }
    if (!(same_hit && same_t && same_p && same_n && same_front && inside && same_uv))
        fprintf(stderr, "%s: hit %d t %d p %d n %d front %d inside %d uv %d\n", what, same_hit, same_t,
                same_p, same_n, same_front, inside, same_uv);
    CHECK(same_hit);
    CHECK(same_t);
    CHECK(same_p);
    CHECK(same_n);
    CHECK(same_front);
    CHECK(inside);
    CHECK(same_uv);
    CHECK(hits > RAYS / 2 && misses > RAYS / 2); /* both kinds, over the five transforms */
}

static void test_folds(void)
{
    struct prim s = {.type = PRIM_SPHERE};
    s.g.sphere.center = v3(143.6, 108.47, 23.34), s.g.sphere.radius = 10;
    check_fold(&s, "sphere", any_turns);

    struct prim m = {.type = PRIM_MOVING_SPHERE};
    m.g.msphere.center0 = v3(1, 2, 3), m.g.msphere.velocity = v3(2, -1, 0.5), m.g.msphere.radius = 1.5;
    m.g.msphere.time_lo = 0, m.g.msphere.time_hi = 1;
    check_fold(&m, "moving sphere", any_turns);

    struct prim d = {.type = PRIM_DISK};
    d.g.disk.center = v3(2, 1, -3), d.g.disk.radius = 4;
    onb f = onb_from_w(v3_unit(v3(1, 2, -0.5)));
    d.g.disk.normal = f.w, d.g.disk.e1 = f.u, d.g.disk.e2 = f.v;
    check_fold(&d, "disk", any_turns);

    struct prim c = {.type = PRIM_CYLINDER};
    c.g.cyl.base = v3(0, 0, 0), c.g.cyl.radius = 50;
    c.g.cyl.height = v3_len(v3(120, 120, 120)), c.g.cyl.axis = v3_unit(v3(120, 120, 120));
    check_fold(&c, "cylinder", any_turns);

    struct prim t = {.type = PRIM_TRIANGLE};
    t.g.tri.v0 = v3(0, 140, 0), t.g.tri.e1 = v3(-100.8, -140, -100.8), t.g.tri.e2 = v3(140, -140, 0);
    t.g.tri.normal = v3_unit(v3_cross(t.g.tri.e1, t.g.tri.e2));
    check_fold(&t, "triangle", any_turns);

    /* rects stay axis-aligned under quarter turns: every plane, both faces */
    for (int axis = 0; axis < 3; axis++)
        for (int flip = 0; flip < 2; flip++) {
            struct prim r = {.type = PRIM_RECT, .flip = flip};
            r.g.rect.axis = axis, r.g.rect.k = 3.25;
            r.g.rect.a0 = -2, r.g.rect.a1 = 5, r.g.rect.b0 = 1, r.g.rect.b1 = 2.5;
            char what[32];
            snprintf(what, sizeof what, "rect axis %d flip %d", axis, flip);
            check_fold(&r, what, quarter_turns);
        }
}

/* Boxes, media and rects turned by other than quarter turns keep their transform; so do a
   sphere and a quarter-turned rect whose uv a texture reads, and an untransformed prim is left
   as it is. */
static void test_not_folded(void)
{
    struct prim ps[4] = {
        {.type = PRIM_BOX}, {.type = PRIM_RECT}, {.type = PRIM_MEDIUM}, {.type = PRIM_SPHERE}};
    ps[0].g.box.lo = v3(0, 0, 0), ps[0].g.box.hi = v3(1, 2, 3);
    ps[1].g.rect.axis = 1, ps[1].g.rect.a1 = ps[1].g.rect.b1 = 1;
    ps[2].g.medium.center = v3(1, 1, 1), ps[2].g.medium.radius = 2, ps[2].g.medium.neg_inv_density = -1;
    ps[3].g.sphere.center = v3(1, 1, 1), ps[3].g.sphere.radius = 2;
    for (int i = 0; i < 4; i++) {
        struct prim p = ps[i];
        set_xform(&p, 30, v3(1, 2, 3));
        shape_prepare(&p);
        struct prim q = p;
        CHECK(shape_bake(&q, i == 3) == 0);
        CHECK(memcmp(&p, &q, sizeof p) == 0);
    }
    struct prim tr = ps[1];
    set_xform(&tr, 90, v3(1, 2, 3));
    shape_prepare(&tr);
    struct prim tq = tr;
    CHECK(shape_bakes(&tq, 1) == 0 && shape_bake(&tq, 1) == 0 && memcmp(&tr, &tq, sizeof tr) == 0);
    CHECK(shape_bakes(&tq, 0) == 1);
    struct prim s = ps[3];
    shape_prepare(&s);
    struct prim q = s;
    CHECK(shape_bake(&q, 0) == 0 && memcmp(&s, &q, sizeof s) == 0);
}

/* scene_finish folds what it can: the textured sphere (uv) and the box stay transformed. */
static void test_scene_finish(void)
{
    struct scene *sc = scene_new();
    struct texture img = {.type = TEX_IMAGE, .image = 0};
    struct material plain = {.type = MAT_LAMBERTIAN, .albedo = v3(0.5, 0.5, 0.5), .texture = -1};
    struct material textured = {.type = MAT_LAMBERTIAN, .texture = 0};
    scene_add_texture(sc, &img);
    scene_add_material(sc, &plain);
    scene_add_material(sc, &textured);
    struct prim s = {.type = PRIM_SPHERE, .material = 0}, b = {.type = PRIM_BOX, .material = 0};
    s.g.sphere.center = v3(1, 0, 0), s.g.sphere.radius = 1;
    b.g.box.lo = v3(0, 0, 0), b.g.box.hi = v3(1, 1, 1);
    set_xform(&s, 90, v3(0, 0, 5));
    set_xform(&b, 90, v3(0, 0, -5));
    scene_add_prim(sc, &s);
    s.material = 1;
    scene_add_prim(sc, &s);
    scene_add_prim(sc, &b);
    struct err e;
    CHECK(scene_finish(sc, &e) == 0);
    CHECK(!sc->prims[0].has_xform && sc->prims[1].has_xform && sc->prims[2].has_xform);
    /* (1, 0, 0) turned 90 degrees about y is (0, 0, -1); then moved by (0, 0, 5) */
    vec3 c = sc->prims[0].g.sphere.center;
    CHECK_NEAR(c.x, 0, 1e-12);
    CHECK_NEAR(c.z, 4, 1e-12);
    scene_free(sc);
}

int main(void)
{
    test_folds();
    test_not_folded();
    test_scene_finish();
    return check_report("test_shape_bake");
}
