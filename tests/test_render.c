/* Tests for rng, camera, shapes, BVH and the integrator's invariants. */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "geom/bvh.h"
#include "geom/camera.h"
#include "check.h"
#include "geom/packet.h"
#include "render/render.h"
#include "base/rng.h"
#include "geom/shape.h"
#include "geom/shape_light_inline.h"

static void test_rng(void)
{
    struct rng a, b, c;
    rng_seed(&a, 42, 1);
    rng_seed(&b, 42, 1);
    rng_seed(&c, 42, 2);
    int same = 1, diff_stream = 0;
    for (int i = 0; i < 1000; i++) {
        uint32_t x = rng_u32(&a), y = rng_u32(&b), z = rng_u32(&c);
        same &= x == y;
        diff_stream += x != z;
    }
    CHECK(same);
    CHECK(diff_stream > 990);
    /* rng_uniform_pair's jump-ahead: two rng_uniform draws, bit for bit, and the same state */
    int pair_same = 1;
    for (uint64_t k = 0; k < 20000; k++) {
        struct rng p, q;
        rng_seed(&p, rng_mix64(k), k % 7 == 0 ? k : rng_mix64(k + 99));
        q = p;
        double u, v;
        rng_uniform_pair(&p, &u, &v);
        double u2 = rng_uniform(&q), v2 = rng_uniform(&q);
        pair_same &= memcmp(&u, &u2, sizeof u) == 0 && memcmp(&v, &v2, sizeof v) == 0 && p.state == q.state &&
                     p.inc == q.inc;
    }
    CHECK(pair_same);
    /* rng_peek_u32 gives the value rng_u32 returns next and leaves the stream where it was (the
       render's prefetch of the next pool point relies on both). */
    struct rng pk;
    rng_seed(&pk, 42, 7);
    for (int i = 0; i < 100; i++) {
        struct rng before = pk;
        uint32_t peeked = rng_peek_u32(&pk);
        CHECK(pk.state == before.state && pk.inc == before.inc);
        CHECK(peeked == rng_u32(&pk));
    }
    /* Uniform in [0,1), mean 1/2, variance 1/12. */
    double sum = 0, sum2 = 0;
    int in_range = 1;
    const int n = 200000;
    for (int i = 0; i < n; i++) {
        double u = rng_uniform(&a);
        in_range &= u >= 0 && u < 1;
        sum += u;
        sum2 += u * u;
    }
    CHECK(in_range);
    CHECK_NEAR(sum / n, 0.5, 0.005);
    CHECK_NEAR(sum2 / n - (sum / n) * (sum / n), 1.0 / 12, 0.002);
    /* Neighbouring pixels' streams are uncorrelated: correlation of first draws near 0. */
    double sxy = 0, sx = 0, sy = 0, sxx = 0, syy = 0;
    const int m = 20000;
    for (int i = 0; i < m; i++) {
        struct rng p, q;
        rng_pixel(&p, 7, i % 200, i / 200, 0);
        rng_pixel(&q, 7, i % 200 + 1, i / 200, 0);
        double x = rng_uniform(&p), y = rng_uniform(&q);
        sx += x, sy += y, sxy += x * y, sxx += x * x, syy += y * y;
    }
    double cov = sxy / m - (sx / m) * (sy / m);
    double corr = cov / sqrt((sxx / m - (sx / m) * (sx / m)) * (syy / m - (sy / m) * (sy / m)));
    CHECK(fabs(corr) < 0.03);
    /* Pixel streams depend on (seed, x, y, purpose) only. */
    struct rng p1, p2, p3;
    rng_pixel(&p1, 7, 3, 4, 0);
    rng_pixel(&p2, 7, 3, 4, 0);
    rng_pixel(&p3, 7, 4, 3, 0);
    uint32_t v1 = rng_u32(&p1);
    CHECK(v1 == rng_u32(&p2));
    CHECK(v1 != rng_u32(&p3));
    uint32_t below_ok = 1;
    for (int i = 0; i < 1000; i++)
        below_ok &= rng_below(&a, 7) < 7;
    CHECK(below_ok);
}

/* v3_sincos_turn agrees with libm over the whole turn, at the quarter-turn seams too. */
static void test_sincos_turn(void)
{
    double worst = 0;
    for (int i = 0; i <= 100000; i++) {
        double u = i / 100000.0, s, c;
        v3_sincos_turn(u, &s, &c);
        double es = fabs(s - sin(2 * PI * u)), ec = fabs(c - cos(2 * PI * u));
        worst = es > worst ? es : worst;
        worst = ec > worst ? ec : worst;
    }
    CHECK(worst < 2e-15);
    double s, c;
    v3_sincos_turn(0.25, &s, &c);
    CHECK_NEAR(s, 1, 1e-15);
    CHECK_NEAR(c, 0, 1e-15);
    v3_sincos_turn(nextafter(1.0, 0.0), &s, &c);
    CHECK_NEAR(s, 0, 1e-15);
    CHECK_NEAR(c, 1, 1e-15);
}

/* d_sin and d_atan2 agree with libm: d_sin within 1e-15 + 2e-16 |x| over |x| <= 1000, d_atan2
   within 1e-15 over every octant, near the tan(pi/8) seam, and at the signed zeros and axes. */
static void test_sin_atan2(void)
{
    struct rng r;
    rng_seed(&r, 5, 6);
    double worst_sin = 0, worst_atan = 0;
    for (int i = 0; i < 200000; i++) {
        double x = (2 * rng_uniform(&r) - 1) * 1000;
        double e = fabs(d_sin(x) - sin(x)) / (1e-15 + 2e-16 * fabs(x));
        worst_sin = e > worst_sin ? e : worst_sin;
        double a = 2 * rng_uniform(&r) - 1, b = 2 * rng_uniform(&r) - 1;
        if (i % 4 == 1)
            a = 0.41421356237309504880 * b * (1 + (a - 0.5) * 1e-9); /* the seam */
        if (i % 4 == 2)
            b *= 1e-9;
        e = fabs(d_atan2(a, b) - atan2(a, b));
        worst_atan = e > worst_atan ? e : worst_atan;
    }
    CHECK(worst_sin <= 1);
    CHECK(worst_atan < 1e-15);
    const double zs[][2] = {{0, 0}, {-0.0, 0}, {0, -0.0}, {-0.0, -0.0}, {0, -1}, {-0.0, -1},
                            {1, 0}, {-1, 0},   {1, 1},    {-1, -1},     {3, -4}, {-4, 3}};
    int same = 1;
    for (size_t i = 0; i < sizeof zs / sizeof zs[0]; i++) {
        double want = atan2(zs[i][0], zs[i][1]), got = d_atan2(zs[i][0], zs[i][1]);
        same &= fabs(got - want) < 1e-15 && signbit(got) == signbit(want);
    }
    CHECK(same);
    /* finite, but |x| + |y| beyond DBL_MAX: (t - 1) / (t + 1)'s sum overflowed (0 for -0.26) */
    const double big[][2] = {{1e308, 1.7e308}, {-1.7e308, 1e308}, {DBL_MAX, -0.9 * DBL_MAX}};
    int near = 1;
    for (size_t i = 0; i < sizeof big / sizeof big[0]; i++)
        near &= fabs(d_atan2(big[i][0], big[i][1]) - atan2(big[i][0], big[i][1])) < 1e-15;
    CHECK(near);
    CHECK(d_sin(1e300) == sin(1e300));
}

static void test_camera(void)
{
    struct camera cam;
    struct camera_desc d = {v3(0, 0, 0), v3(0, 0, -1), v3(0, 1, 0), 90, 0, 1, 0, 0};
    struct err e;
    CHECK(camera_init(&cam, &d, 2.0, &e) == 0);
    struct rng r;
    rng_seed(&r, 1, 1);
    ray c = camera_ray(&cam, 0.5, 0.5, &r);
    vec3 dir = v3_unit(c.dir);
    CHECK_NEAR(dir.x, 0, 1e-12);
    CHECK_NEAR(dir.y, 0, 1e-12);
    CHECK_NEAR(dir.z, -1, 1e-12);
    /* vfov 90: the top edge is 45 degrees up; aspect 2: the right edge at x = 2 * tan(45). */
    ray top = camera_ray(&cam, 0.5, 1.0, &r);
    CHECK_NEAR(top.dir.y / -top.dir.z, 1.0, 1e-12);
    ray right = camera_ray(&cam, 1.0, 0.5, &r);
    CHECK_NEAR(right.dir.x / -right.dir.z, 2.0, 1e-12);
    ray ll = camera_ray(&cam, 0, 0, &r);
    CHECK(ll.dir.x < 0 && ll.dir.y < 0);
    /* Degenerate cameras are refused. */
    struct camera_desc bad = d;
    bad.vup = v3(0, 0, 1);
    CHECK(camera_init(&cam, &bad, 1, &e) < 0);
    bad = d;
    bad.lookat = bad.lookfrom;
    CHECK(camera_init(&cam, &bad, 1, &e) < 0);
    /* With an aperture, origins spread over the lens but all rays meet at the focus plane. */
    struct camera_desc lens = d;
    lens.aperture = 0.5;
    lens.focus_dist = 3;
    CHECK(camera_init(&cam, &lens, 1, &e) == 0);
    int meet = 1, spread = 0;
    for (int i = 0; i < 100; i++) {
        ray q = camera_ray(&cam, 0.5, 0.5, &r);
        vec3 at = ray_at(&q, (-3 - q.orig.z) / q.dir.z);
        meet &= fabs(at.x) < 1e-9 && fabs(at.y) < 1e-9;
        spread += v3_len(q.orig) > 1e-3;
        meet &= v3_len(q.orig) <= 0.25 + 1e-12;
    }
    CHECK(meet);
    CHECK(spread > 90);
}

static void test_shapes(void)
{
    struct hit h;
    struct prim s = {.type = PRIM_SPHERE};
    s.g.sphere.center = v3(0, 0, -5);
    s.g.sphere.radius = 1;
    ray r = {v3(0, 0, 0), v3(0, 0, -1), 0};
    CHECK(shape_hit(&s, &r, HIT_EPS, DBL_MAX, &h));
    CHECK_NEAR(h.t, 4, 1e-12);
    CHECK(h.front);
    CHECK_NEAR(h.n.z, 1, 1e-12);
    ray miss = {v3(0, 2, 0), v3(0, 0, -1), 0};
    CHECK(!shape_hit(&s, &miss, HIT_EPS, DBL_MAX, &h));
    ray inside = {v3(0, 0, -5), v3(1, 0, 0), 0};
    CHECK(shape_hit(&s, &inside, HIT_EPS, DBL_MAX, &h));
    CHECK(!h.front);
    CHECK_NEAR(h.n.x, -1, 1e-12);
    CHECK(!shape_hit(&s, &r, HIT_EPS, 3.9, &h)); /* t_max excludes the hit */

    /* Rect xz at y=2 facing +y, hit from above and from below. */
    struct prim q = {.type = PRIM_RECT};
    q.g.rect.axis = 1;
    q.g.rect.a0 = -1, q.g.rect.a1 = 1, q.g.rect.b0 = -1, q.g.rect.b1 = 1, q.g.rect.k = 2;
    shape_prepare(&q);
    ray down = {v3(0.5, 5, 0.5), v3(0, -1, 0), 0};
    CHECK(shape_hit(&q, &down, HIT_EPS, DBL_MAX, &h));
    CHECK_NEAR(h.t, 3, 1e-12);
    CHECK(h.front);
    ray up = {v3(0.5, 0, 0.5), v3(0, 1, 0), 0};
    CHECK(shape_hit(&q, &up, HIT_EPS, DBL_MAX, &h));
    CHECK(!h.front);
    q.flip = 1;
    CHECK(shape_hit(&q, &up, HIT_EPS, DBL_MAX, &h));
    CHECK(h.front);
    ray outside = {v3(1.5, 5, 0), v3(0, -1, 0), 0};
    CHECK(!shape_hit(&q, &outside, HIT_EPS, DBL_MAX, &h));
    CHECK_NEAR(shape_area(&q), 4, 1e-12);

    /* Disk facing -z; light points cover the whole radius, uniformly by area. */
    struct prim dk = {.type = PRIM_DISK};
    dk.g.disk.center = v3(0, 0, -2);
    dk.g.disk.radius = 3;
    onb f = onb_from_w(v3(0, 0, 1));
    dk.g.disk.normal = f.w, dk.g.disk.e1 = f.u, dk.g.disk.e2 = f.v;
    shape_prepare(&dk);
    ray at = {v3(2.9, 0, 0), v3(0, 0, -1), 0};
    CHECK(shape_hit(&dk, &at, HIT_EPS, DBL_MAX, &h));
    CHECK(h.front);
    ray past = {v3(3.1, 0, 0), v3(0, 0, -1), 0};
    CHECK(!shape_hit(&dk, &past, HIT_EPS, DBL_MAX, &h));
    int inner = 0, on_disk = 1;
    double maxr = 0;
    struct rng g;
    rng_seed(&g, 3, 3);
    for (int i = 0; i < 10000; i++) {
        vec3 p = light_point(&dk, (struct pt2){rng_uniform(&g), rng_uniform(&g)});
        double rr = v3_len(v3_sub(p, dk.g.disk.center));
        on_disk &= rr <= 3 + 1e-9 && fabs(p.z + 2) < 1e-9;
        maxr = rr > maxr ? rr : maxr;
        inner += rr < 1.5;
    }
    CHECK(on_disk);
    CHECK(maxr > 2.9); /* the seed's bug sampled a radius-1 spot only */
    CHECK_NEAR(inner / 10000.0, 0.25, 0.02);
    /* Solid-angle pdf of a small disk seen head-on from far: dist^2 / area. */
    double pdf = light_pdf(&dk, v3(0, 0, 8), v3(0, 0, -1));
    CHECK_NEAR(pdf, 100 / (PI * 9), 1e-9);
    CHECK(light_pdf(&dk, v3(0, 0, 8), v3(0, 1, 0)) == 0);

    /* Transform: a unit sphere translated to x=10. */
    struct prim t = s;
    t.g.sphere.center = v3(0, 0, 0);
    t.has_xform = 1, t.cos_y = 1, t.sin_y = 0, t.offset = v3(10, 0, 0);
    ray tr = {v3(10, 0, 5), v3(0, 0, -1), 0};
    CHECK(shape_hit(&t, &tr, HIT_EPS, DBL_MAX, &h));
    CHECK_NEAR(h.p.x, 10, 1e-12);
    CHECK_NEAR(h.p.z, 1, 1e-12);
}

/* A BVH over a grid of spheres finds the same nearest hit as a linear scan. */
static void test_bvh(void)
{
    struct scene *sc = scene_new();
    struct material m = {.type = MAT_LAMBERTIAN, .albedo = v3(0.5, 0.5, 0.5), .texture = -1};
    scene_add_material(sc, &m);
    struct rng r;
    rng_seed(&r, 9, 9);
    for (int i = 0; i < 500; i++) {
        struct prim p = {.type = PRIM_SPHERE, .material = 0};
        p.g.sphere.center =
            v3(rng_uniform(&r) * 20 - 10, rng_uniform(&r) * 20 - 10, rng_uniform(&r) * 20 - 10);
        p.g.sphere.radius = 0.1 + rng_uniform(&r) * 0.5;
        scene_add_prim(sc, &p);
    }
    struct err e;
    CHECK(scene_finish(sc, &e) == 0);
    CHECK(sc->n_nodes > 1 && sc->n_nodes < 2 * sc->n_prims);
    int agree = 1, hits = 0;
    for (int k = 0; k < 2000; k++) {
        ray q = {v3(0, 0, -30), v3(rng_uniform(&r) - 0.5, rng_uniform(&r) - 0.5, 1), 0};
        struct hit a, b;
        int ga = bvh_hit(sc, &q, HIT_EPS, DBL_MAX, &a);
        int gb = 0;
        double tmax = DBL_MAX;
        for (int i = 0; i < sc->n_prims; i++)
            if (shape_hit(&sc->prims[i], &q, HIT_EPS, tmax, &b)) {
                tmax = b.t;
                gb = 1;
            }
        agree &= ga == gb && (!ga || fabs(a.t - tmax) < 1e-9);
        hits += ga;
    }
    CHECK(agree);
    CHECK(hits > 100);
    scene_free(sc);
}

/* A white furnace: a closed diffuse sphere of albedo a lit by nothing but a background of 1
   seen from inside returns a^k... simpler invariant: inside a sphere of albedo 0.5 with
   background 1 outside, a lambertian interior never lets light in, so radiance is 0. And an
   empty scene with background c returns exactly c for every sample. */
static void test_integrator(void)
{
    struct scene *sc = scene_new();
    sc->background = v3(0.25, 0.5, 0.75);
    struct err e;
    CHECK(scene_finish(sc, &e) == 0);
    struct camera cam;
    struct camera_desc d = {v3(0, 0, 0), v3(0, 0, -1), v3(0, 1, 0), 60, 0, 1, 0, 0};
    camera_init(&cam, &d, 1, &e);
    struct sampler *pix = sampler_new(SAMPLER_RANDOM, 50, 0, 0, &e);
    CHECK(pix != NULL);
    if (!pix) {
        scene_free(sc);
        return;
    }
    struct render_settings rs = {4, 4, 10, 1, 0, 0, 0, 0};
    struct render_ctx *ctx = render_ctx_new(sc, &cam, &rs, pix, NULL, &e);
    CHECK(ctx != NULL);
    struct render_stats st;
    render_stats_init(&st);
    float rgb[3];
    render_pixel(ctx, 1, 2, rgb, &st);
    CHECK_NEAR(rgb[0], 0.25, 1e-6);
    CHECK_NEAR(rgb[1], 0.5, 1e-6);
    CHECK_NEAR(rgb[2], 0.75, 1e-6);
    CHECK(st.samples == 4 && st.spp_min == 4 && st.spp_max == 4 && st.rays == 4);
    /* The same pixel twice gives the same value (no hidden state across pixels). */
    float again[3];
    render_pixel(ctx, 3, 3, again, &st);
    render_pixel(ctx, 1, 2, again, &st);
    CHECK(again[0] == rgb[0] && again[1] == rgb[1] && again[2] == rgb[2]);
    render_ctx_free(ctx);
    sampler_free(pix);
    scene_free(sc);
}

/* Pixel (1, 2) of a 4x4 render of sc (finished here, then freed) through camera d: jittered
   pixel points at threshold pixel_t, a jittered light sampler at light_t (0: none), paths of at
   most depth segments. Its value goes to rgb, its counters are returned. */
static struct render_stats pixel_of(struct scene *sc, const struct camera_desc *d, double pixel_t,
                                    double light_t, int depth, float rgb[3])
{
    struct err e;
    CHECK(scene_finish(sc, &e) == 0);
    struct camera cam;
    camera_init(&cam, d, 1, &e);
    struct sampler *pix = sampler_new(SAMPLER_JITTER, pixel_t, 0, 0, &e);
    struct sampler *lsm = light_t > 0 ? sampler_new(SAMPLER_JITTER, light_t, 0, 0, &e) : NULL;
    struct render_settings rs = {4, 4, depth, 1, 0, 0, 0, 0};
    struct render_ctx *ctx =
        pix && (lsm || light_t <= 0) ? render_ctx_new(sc, &cam, &rs, pix, lsm, &e) : NULL;
    CHECK(ctx != NULL);
    struct render_stats st;
    render_stats_init(&st);
    rgb[0] = rgb[1] = rgb[2] = -1;
    if (ctx)
        render_pixel(ctx, 1, 2, rgb, &st);
    render_ctx_free(ctx);
    sampler_free(pix);
    sampler_free(lsm);
    scene_free(sc);
    return st;
}

/* A pixel's value in a scene of one medium sphere (density 0.3, radius 3) around the camera under
   a background of 1: its isotropic material has albedo `albedo` and, when textured, a checker
   whose squares are both `tex`. */
static float medium_pixel(vec3 albedo, int textured, vec3 tex)
{
    struct scene *sc = scene_new();
    sc->background = v3(1, 1, 1);
    struct texture t = {.type = TEX_CHECKER, .odd = tex, .even = tex, .scale = 1};
    int ti = scene_add_texture(sc, &t);
    struct material m = {.type = MAT_ISOTROPIC, .albedo = albedo, .texture = textured ? ti : -1};
    scene_add_material(sc, &m);
    struct prim p = {.type = PRIM_MEDIUM, .material = 0};
    p.g.medium.center = v3(0, 0, 0);
    p.g.medium.radius = 3;
    p.g.medium.neg_inv_density = -1 / 0.3;
    scene_add_prim(sc, &p);
    struct camera_desc d = {v3(0, 0, 0), v3(0, 0, -1), v3(0, 1, 0), 60, 0, 1, 0, 0};
    float rgb[3];
    struct render_stats st = pixel_of(sc, &d, 50, 0, 10, rgb);
    CHECK(st.rays > st.samples); /* the paths scatter in the medium */
    return rgb[0];
}

/* The isotropic branch takes a medium's albedo from its texture when it has one, else from the
   material: the same paths (the texture does not draw random numbers), so a plain albedo of 0.5
   and a texture of 0.5 over an ignored albedo of 1 give the same pixel, and a texture of 1 the
   brighter one of a plain albedo of 1. */
static void test_medium_albedo(void)
{
    const vec3 half = v3(0.5, 0.5, 0.5), one = v3(1, 1, 1);
    float plain = medium_pixel(half, 0, one), textured = medium_pixel(one, 1, half);
    float white = medium_pixel(one, 0, half), white_tex = medium_pixel(half, 1, one);
    CHECK(plain > 0 && plain < 0.9f && plain == textured);
    CHECK(white > plain && white == white_tex);
}

/* A diffuse floor (xz rect at y = 0) under a rect light facing down at y = 2 (not finished). */
static struct scene *floor_scene(void)
{
    struct scene *sc = scene_new();
    struct material white = {.type = MAT_LAMBERTIAN, .albedo = v3(0.5, 0.5, 0.5), .texture = -1};
    struct material lamp = {.type = MAT_LIGHT, .emit = v3(4, 4, 4), .texture = -1};
    scene_add_material(sc, &white);
    scene_add_material(sc, &lamp);
    struct prim fl = {.type = PRIM_RECT, .material = 0}, li = {.type = PRIM_RECT, .material = 1, .flip = 1};
    fl.g.rect.axis = li.g.rect.axis = 1;
    fl.g.rect.a0 = fl.g.rect.b0 = -50, fl.g.rect.a1 = fl.g.rect.b1 = 50, fl.g.rect.k = 0;
    li.g.rect.a0 = li.g.rect.b0 = -0.5, li.g.rect.a1 = li.g.rect.b1 = 0.5, li.g.rect.k = 2;
    scene_add_prim(sc, &fl);
    scene_add_light(sc, scene_add_prim(sc, &li));
    return sc;
}

/* floor_scene seen from above: one pixel's stats at max_depth depth. */
static struct render_stats floor_pixel(int depth)
{
    struct scene *sc = floor_scene();
    struct camera_desc d = {v3(0, 1, -1), v3(0, 0, 0.5), v3(0, 1, 0), 20, 0, 1, 0, 0}; /* at the floor */
    float rgb[3];
    return pixel_of(sc, &d, 25, 50, depth, rgb);
}

/* A path's last segment only looks for emission: a surface hit there scatters nothing, so no
   light point is drawn for it; one segment more and the floor's bounces draw light sets. */
static void test_last_segment(void)
{
    struct render_stats one = floor_pixel(1), two = floor_pixel(2);
    CHECK(one.samples == 16 && one.rays == 16);
    CHECK(one.light_sets == 0);
    CHECK(two.rays > 16 && two.light_sets > 0);
}

/* A closed unit box of six diffuse walls with a lamp under its ceiling, seen from inside (the
   camera at (x, y)) under a background of 1e30: one node, so render_pixel traces its paths in
   lanes, four at a time (render_lanes.c), and a pixel's last path alone (bvh_hit_node). No path
   escapes the box, so the background never shows; a lane that lost its hit would add 1e30 times
   its weight (3 of these 25 pixels end with lane 1 alone). */
static void closed_box_pixel(double x, double y, float rgb[3])
{
    struct scene *sc = scene_new();
    sc->background = v3(1e30, 1e30, 1e30);
    struct material white = {.type = MAT_LAMBERTIAN, .albedo = v3(0.5, 0.5, 0.5), .texture = -1};
    struct material lamp = {.type = MAT_LIGHT, .emit = v3(4, 4, 4), .texture = -1};
    scene_add_material(sc, &white);
    scene_add_material(sc, &lamp);
    for (int w = 0; w < 6; w++) {
        struct prim wall = {.type = PRIM_RECT, .material = 0};
        wall.g.rect.axis = w / 2;
        wall.g.rect.a1 = wall.g.rect.b1 = 1, wall.g.rect.k = w % 2;
        scene_add_prim(sc, &wall);
    }
    struct prim li = {.type = PRIM_RECT, .material = 1, .flip = 1};
    li.g.rect.axis = 1;
    li.g.rect.a0 = li.g.rect.b0 = 0.2, li.g.rect.a1 = li.g.rect.b1 = 0.8, li.g.rect.k = 0.99;
    scene_add_light(sc, scene_add_prim(sc, &li));
    struct camera_desc d = {v3(x, y, 0.9), v3(x, y, 0), v3(0, 1, 0), 60, 0, 1, 0, 0};
    struct render_stats st = pixel_of(sc, &d, 6.25, 25, 50, rgb);
    CHECK(st.samples == 256 && st.rays > 2 * st.samples);
}

/* floor_pixel's scene (floor, lamp above) at max_depth 2 with next-event estimation, pixel
   sets of 16 points and light sets of 4 (sampler_dims: all when dims), 4x4 pixels; spread: with
   40 spheres far below the floor (never reached), so that the scene has more than one BVH node
   and its paths are traced one by one, not in lanes; shutter: the camera's shutter open over
   [0, 1] (shutter 2: and a moving sphere far below the floor, never reached). The stats of pixel
   (1, 2). */
static struct render_stats work_pixel(int spread, int dims, int shutter)
{
    struct scene *sc = floor_scene();
    for (int i = 0; spread && i < 40; i++) {
        struct prim ball = {.type = PRIM_SPHERE, .material = 0};
        ball.g.sphere.center = v3(40 * i, -100 - 30 * i, 0), ball.g.sphere.radius = 1;
        scene_add_prim(sc, &ball);
    }
    if (shutter == 2) {
        struct prim ball = {.type = PRIM_MOVING_SPHERE, .material = 0};
        ball.g.msphere.center0 = v3(0, -100, 0), ball.g.msphere.velocity = v3(1, 0, 0);
        ball.g.msphere.radius = 1, ball.g.msphere.time_hi = 1;
        scene_add_prim(sc, &ball);
    }
    struct err e;
    CHECK(scene_finish(sc, &e) == 0);
    CHECK(packet_usable(sc) == (!spread && shutter < 2));
    struct camera_desc d = {v3(0, 1, -1), v3(0, 0, 0.5), v3(0, 1, 0), 20, 0, 1, 0, shutter ? 1 : 0};
    struct camera cam;
    camera_init(&cam, &d, 1, &e);
    struct sampler *pix = sampler_new(SAMPLER_JITTER, 25, 0, 0, &e),
                   *lsm = sampler_new(SAMPLER_JITTER, 50, 0, 0, &e);
    struct render_settings rs = {4, 4, 2, 1, 0, 1, dims, 0};
    struct render_ctx *ctx = render_ctx_new(sc, &cam, &rs, pix, lsm, &e);
    CHECK(ctx != NULL);
    struct render_stats st;
    render_stats_init(&st);
    float rgb[3];
    if (ctx)
        render_pixel(ctx, 1, 2, rgb, &st);
    render_ctx_free(ctx);
    sampler_free(pix);
    sampler_free(lsm);
    scene_free(sc);
    return st;
}

/* Issue 35: the work counts are counted alike in lanes (render_lanes.c) and one path at a time.
   Every one of the 16 camera rays reaches the floor, which sends one shadow ray to the lamp and
   one scattered ray (the last segment): 32 path segments, 16 shadow rays, 16 light points in 4
   sets of 4; under sampler_dims: all the floor's decisions come from the padded sets instead:
   its light point and direction, 32 points of 2 sets (the lamp is the only emitter: no light
   choice is drawn). */
static void test_work_counts(void)
{
    for (int spread = 0; spread < 2; spread++) {
        struct render_stats st = work_pixel(spread, 0, 0);
        CHECK(st.samples == 16 && st.pixel_points == 16 && st.rays == 48 && st.shadow_rays == 16);
        CHECK(st.light_points == 16 && st.light_sets == 4 && st.padded_points == 0 && st.padded_sets == 0);
        st = work_pixel(spread, 1, 0);
        CHECK(st.samples == 16 && st.rays == 48 && st.shadow_rays == 16);
        CHECK(st.light_points == 0 && st.light_sets == 0 && st.padded_points == 32 && st.padded_sets == 2);
    }
}

/* Under sampler_dims: all the shutter time is a decision only where a hit depends on it: with
   the shutter open over [0, 1] the floor scene's samples read no time set (32 points of 2 sets, as
   with a closed shutter); with a moving sphere in the scene they read it (48 points of 3 sets). */
static void test_time_read(void)
{
    struct render_stats st = work_pixel(0, 1, 1);
    CHECK(st.samples == 16 && st.padded_points == 32 && st.padded_sets == 2);
    st = work_pixel(0, 1, 2);
    CHECK(st.samples == 16 && st.padded_points == 48 && st.padded_sets == 3);
}

static void test_closed_box(void)
{
    for (int i = 0; i < 25; i++) {
        float rgb[3];
        closed_box_pixel(0.1 + 0.2 * (i % 5), 0.1 + 0.2 * (i / 5), rgb);
        for (int k = 0; k < 3; k++)
            CHECK(rgb[k] > 0 && rgb[k] < 10);
    }
}

/* The sidecar's sampler_s: one pixel in eight is timed whole with every draw inside it. In a
   scene of nothing but the background a fresh Poisson set per pixel (~260 points, ~0.1 ms) is
   nearly all of a pixel's time, so the draws' share must come out near 1 and never above it,
   however few pixels a process renders (a small image over several processes, a --part) and
   however busy the machine (a timed draw counted for the next seven untimed ones made the
   sidecar's share 2.1). render_stats_finish then makes sampler_s a part of the CPU time given.
   Three tries for the lower bound: a time slice lost between draws counts against it. One
   CHECK each whatever the tries, so the suite's count does not depend on them. Pixels: how
   many of the 16 x 16 to render, in order. */
static double sampler_share_of_render(int pixels, int *bounded)
{
    struct scene *sc = scene_new();
    struct err e;
    const int finished = scene_finish(sc, &e) == 0;
    struct camera cam;
    struct camera_desc d = {v3(0, 0, 0), v3(0, 0, -1), v3(0, 1, 0), 60, 0, 1, 0, 0};
    camera_init(&cam, &d, 1, &e);
    struct sampler *pix = sampler_new(SAMPLER_POISSON, 5, 0, 0, &e);
    struct render_settings rs = {16, 16, 4, 1, 0, 0, 0, 0};
    struct render_ctx *ctx = finished && pix ? render_ctx_new(sc, &cam, &rs, pix, NULL, &e) : NULL;
    struct render_stats st;
    render_stats_init(&st);
    float rgb[3];
    for (int p = 0; ctx && p < pixels; p++)
        render_pixel(ctx, p % rs.width, p / rs.width, rgb, &st);
    render_ctx_free(ctx);
    sampler_free(pix);
    scene_free(sc);
    render_stats_finish(&st, 1);
    double share = st.sampler_s;
    render_stats_finish(&st, 0.25);
    *bounded = st.timed_draw_ns <= st.timed_pixel_ns && share >= 0 && share <= 1 && st.sampler_s <= 0.25 &&
               st.sampler_s == share * 0.25;
    return ctx ? share : 0; /* 0 (a failure) without a render */
}

static void test_sampler_time(void)
{
    const int pixels[] = {256, 2, 9};
    for (int k = 0; k < 3; k++) {
        double share = 0;
        int bounded = 1, b;
        for (int i = 0; i < 3 && !(share > 0.6); i++) {
            share = sampler_share_of_render(pixels[k], &b);
            bounded &= b;
        }
        if (!(share > 0.6 && bounded))
            fprintf(stderr, "draws of %d pixels: %.3f of the timed pixels' time\n", pixels[k], share);
        CHECK(share > 0.6);
        CHECK(bounded);
    }
}

int main(void)
{
    test_rng();
    test_sincos_turn();
    test_sin_atan2();
    test_camera();
    test_shapes();
    test_bvh();
    test_integrator();
    test_medium_albedo();
    test_last_segment();
    test_work_counts();
    test_time_read();
    test_closed_box();
    test_sampler_time();
    return check_report("test_render");
}
