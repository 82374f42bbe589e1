/* Tests for the scene primitives: box, cylinder, triangle, moving sphere and medium hits,
   bounds that enclose every hit, and light sampling whose pdf matches its directions. */
#include <float.h>
#include <string.h>

#include "check.h"
#include "base/rng.h"
#include "geom/scene.h"
#include "geom/shape.h"
#include "geom/shape_light_inline.h"

static void set_xform(struct prim *p, double deg, vec3 offset)
{
    p->has_xform = 1;
    p->cos_y = cos(deg * PI / 180);
    p->sin_y = sin(deg * PI / 180);
    p->offset = offset;
}

static void test_box(void)
{
    struct hit h;
    struct prim b = {.type = PRIM_BOX};
    b.g.box.lo = v3(0, 0, 0);
    b.g.box.hi = v3(1, 2, 3);
    ray r = {v3(0.5, 1, -5), v3(0, 0, 1), 0};
    CHECK(shape_hit(&b, &r, HIT_EPS, DBL_MAX, &h));
    CHECK_NEAR(h.t, 5, 1e-12);
    CHECK(h.front);
    CHECK_NEAR(h.n.z, -1, 1e-12);
    CHECK(!signbit(h.n.x) && !signbit(h.n.y));
    ray inside = {v3(0.5, 1, 1), v3(1, 0, 0), 0};
    CHECK(shape_hit(&b, &inside, HIT_EPS, DBL_MAX, &h));
    CHECK_NEAR(h.t, 0.5, 1e-12);
    CHECK(!h.front);
    CHECK_NEAR(h.n.x, -1, 1e-12);            /* faces against the ray: the outward +x normal flipped */
    CHECK(signbit(h.n.y) && signbit(h.n.z)); /* its zeros too, as set_face flips them */
    ray miss = {v3(1.5, 1, -5), v3(0, 0, 1), 0};
    CHECK(!shape_hit(&b, &miss, HIT_EPS, DBL_MAX, &h));
    ray parallel = {v3(0.5, 3, -5), v3(0, 0, 1), 0}; /* above the box, parallel to y slabs */
    CHECK(!shape_hit(&b, &parallel, HIT_EPS, DBL_MAX, &h));
    ray top = {v3(0.25, 10, 0.5), v3(0, -2, 0), 0};
    CHECK(shape_hit(&b, &top, HIT_EPS, DBL_MAX, &h));
    CHECK_NEAR(h.t, 4, 1e-12);
    CHECK_NEAR(h.n.y, 1, 1e-12);
    /* Rotated 90 degrees about y and moved: the 3-deep z extent now lies along x. */
    set_xform(&b, 90, v3(10, 0, 0));
    ray side = {v3(20, 1, -0.5), v3(-1, 0, 0), 0};
    CHECK(shape_hit(&b, &side, HIT_EPS, DBL_MAX, &h));
    CHECK_NEAR(h.p.x, 13, 1e-9);
    CHECK_NEAR(h.n.x, 1, 1e-9);
    /* Parallel to a slab with the origin on its plane (+0 and -0 directions): inside it. */
    struct prim u = {.type = PRIM_BOX};
    u.g.box.lo = v3(0, 0, 0), u.g.box.hi = v3(1, 2, 3);
    for (int k = 0; k < 4; k++) {
        double zero = k & 1 ? -0.0 : 0.0, plane = k & 2 ? 2 : 0;
        ray on = {v3(-1, plane, 1), v3(1, zero, 0), 0};
        CHECK(shape_hit(&u, &on, HIT_EPS, DBL_MAX, &h) && h.t == 1 && h.front && h.n.x == -1);
        ray off = {v3(-1, plane + (k & 2 ? 1e-9 : -1e-9), 1), v3(1, zero, 0), 0};
        CHECK(!shape_hit(&u, &off, HIT_EPS, DBL_MAX, &h));
    }
}

/* The slab test as written before its planes were picked by the sign bit of d: by the sign of
   inv = 1 / d, the entry face from outside, the exit face from inside. */
static int book_box(const struct prim *b, const ray *r, double t_min, double t_max, double *t, int *axis)
{
    double lo[3] = {b->g.box.lo.x, b->g.box.lo.y, b->g.box.lo.z},
           hi[3] = {b->g.box.hi.x, b->g.box.hi.y, b->g.box.hi.z};
    double o[3] = {r->orig.x, r->orig.y, r->orig.z}, d[3] = {r->dir.x, r->dir.y, r->dir.z};
    double t_near = -INFINITY, t_far = INFINITY;
    int near_axis = 0, far_axis = 0;
    for (int a = 0; a < 3; a++) {
        double inv = 1.0 / d[a];
        double tn = ((inv < 0 ? hi[a] : lo[a]) - o[a]) * inv, tf = ((inv < 0 ? lo[a] : hi[a]) - o[a]) * inv;
        if (tn > t_near)
            t_near = tn, near_axis = a;
        if (tf < t_far)
            t_far = tf, far_axis = a;
    }
    if (t_near > t_far)
        return 0;
    int entry = t_near > t_min && t_near < t_max;
    if (!entry && !(t_far > t_min && t_far < t_max))
        return 0;
    *t = entry ? t_near : t_far;
    *axis = entry ? near_axis : far_axis;
    return 1;
}

/* shape_hit's box against book_box on random rays, a third of their direction components +0 or
   -0 and a third of their origins on a face's plane: the same answer, t and face. */
static void test_box_as_book(void)
{
    struct rng g;
    rng_seed(&g, 12, 12);
    struct prim b = {.type = PRIM_BOX};
    b.g.box.lo = v3(-1, 0, 2), b.g.box.hi = v3(1, 3, 2.5);
    int same = 1, hits = 0;
    for (int i = 0; i < 100000; i++) {
        double o[3], d[3], lo[3] = {-1, 0, 2}, hi[3] = {1, 3, 2.5};
        for (int a = 0; a < 3; a++) {
            unsigned k = rng_below(&g, 6);
            o[a] = k == 0 ? lo[a] : k == 1 ? hi[a] : 8 * rng_uniform(&g) - 4;
            k = rng_below(&g, 6);
            d[a] = k == 0 ? 0.0 : k == 1 ? -0.0 : rng_uniform(&g) - 0.5;
        }
        ray r = {v3(o[0], o[1], o[2]), v3(d[0], d[1], d[2]), 0};
        double t = 0;
        int axis = 0;
        struct hit h;
        int want = book_box(&b, &r, HIT_EPS, DBL_MAX, &t, &axis),
            got = shape_hit(&b, &r, HIT_EPS, DBL_MAX, &h);
        same &= want == got && (!got || (h.t == t && v3_get(h.n, axis) != 0));
        hits += got;
    }
    CHECK(same);
    CHECK(hits > 5000);
}

/* A transformed box's hit is the plain box's hit of the ray moved to object space, moved back:
   the same arithmetic, so the same bits, the zeros' signs included (onb_from_w reads them). */
static void test_box_xform(void)
{
    struct prim b = {.type = PRIM_BOX}, x;
    b.g.box.lo = v3(0, 0, 0), b.g.box.hi = v3(120, 330, 120);
    x = b;
    set_xform(&x, 10, v3(400, 0, 295));
    struct rng g;
    rng_seed(&g, 4, 4);
    int same = 1, hits = 0;
    for (int i = 0; i < 20000; i++) {
        vec3 o = v3(555 * rng_uniform(&g), 555 * rng_uniform(&g), 555 * rng_uniform(&g));
        vec3 d =
            v3_sub(v3(380 + 160 * rng_uniform(&g), 340 * rng_uniform(&g), 280 + 160 * rng_uniform(&g)), o);
        if (i % 4 == 0) /* parallel to the y slabs, as a level ray is */
            d.y = i % 8 ? 0.0 : -0.0;
        ray r = {o, d, 0};
        vec3 w = v3_sub(o, x.offset);
        ray q = {v3(x.cos_y * w.x - x.sin_y * w.z, w.y, x.sin_y * w.x + x.cos_y * w.z),
                 v3(x.cos_y * d.x - x.sin_y * d.z, d.y, x.sin_y * d.x + x.cos_y * d.z), 0};
        struct hit hx, hb;
        int gx = shape_hit(&x, &r, HIT_EPS, DBL_MAX, &hx), gb = shape_hit(&b, &q, HIT_EPS, DBL_MAX, &hb);
        same &= gx == gb;
        if (!gx || !gb)
            continue;
        hits++;
        vec3 p = v3(x.cos_y * hb.p.x + x.sin_y * hb.p.z, hb.p.y, -x.sin_y * hb.p.x + x.cos_y * hb.p.z);
        vec3 n = v3(x.cos_y * hb.n.x + x.sin_y * hb.n.z, hb.n.y, -x.sin_y * hb.n.x + x.cos_y * hb.n.z);
        p = v3_add(p, x.offset);
        same &= hx.t == hb.t && hx.front == hb.front && !memcmp(&hx.p, &p, sizeof p) &&
                !memcmp(&hx.n, &n, sizeof n);
    }
    CHECK(same);
    CHECK(hits > 2000);
}

static void test_cylinder(void)
{
    struct hit h;
    struct prim c = {.type = PRIM_CYLINDER};
    vec3 axis = v3_unit(v3(1, 1, 1));
    c.g.cyl.base = v3(0, 0, 0);
    c.g.cyl.axis = axis;
    c.g.cyl.height = sqrt(3.0) * 4;
    c.g.cyl.radius = 1;
    /* A ray through the axis midpoint, perpendicular to it, hits the side at distance 1. */
    vec3 mid = v3(2, 2, 2), perp = v3_unit(v3(1, -1, 0));
    ray r = {v3_fma(mid, perp, 5), v3_neg(perp), 0};
    CHECK(shape_hit(&c, &r, HIT_EPS, DBL_MAX, &h));
    CHECK_NEAR(h.t, 4, 1e-9);
    CHECK_NEAR(v3_dot(h.n, perp), 1, 1e-9);
    CHECK(h.front);
    /* Along the axis from below: the base cap, normal -axis, then from inside the top cap. */
    ray up = {v3_fma(v3_fma(v3(0, 0, 0), axis, -3), perp, 0.5), axis, 0};
    CHECK(shape_hit(&c, &up, HIT_EPS, DBL_MAX, &h));
    CHECK_NEAR(h.t, 3, 1e-9);
    CHECK_NEAR(v3_dot(h.n, axis), -1, 1e-9);
    ray in = {v3_fma(mid, perp, 0.5), axis, 0};
    CHECK(shape_hit(&c, &in, HIT_EPS, DBL_MAX, &h));
    CHECK_NEAR(h.t, sqrt(3.0) * 2, 1e-9);
    CHECK(!h.front);
    /* Past the top: the infinite side would be hit, the capped cylinder is not. */
    vec3 beyond = v3_fma(v3(0, 0, 0), axis, sqrt(3.0) * 4 + 0.5);
    ray over = {v3_fma(beyond, perp, 5), v3_neg(perp), 0};
    CHECK(!shape_hit(&c, &over, HIT_EPS, DBL_MAX, &h));
    /* Outside the radius along the axis direction: misses the caps. */
    ray wide = {v3_fma(v3_fma(v3(0, 0, 0), axis, -3), perp, 1.5), axis, 0};
    CHECK(!shape_hit(&c, &wide, HIT_EPS, DBL_MAX, &h));
}

static void test_triangle(void)
{
    struct hit h;
    struct prim t = {.type = PRIM_TRIANGLE};
    t.g.tri.v0 = v3(0, 0, 0);
    t.g.tri.e1 = v3(1, 0, 0);
    t.g.tri.e2 = v3(0, 1, 0);
    t.g.tri.normal = v3(0, 0, 1);
    ray r = {v3(0.25, 0.25, 2), v3(0, 0, -1), 0};
    CHECK(shape_hit(&t, &r, HIT_EPS, DBL_MAX, &h));
    CHECK_NEAR(h.t, 2, 1e-12);
    CHECK(h.front);
    CHECK_NEAR(h.n.z, 1, 1e-12);
    ray back = {v3(0.25, 0.25, -2), v3(0, 0, 1), 0};
    CHECK(shape_hit(&t, &back, HIT_EPS, DBL_MAX, &h));
    CHECK(!h.front);
    CHECK_NEAR(h.n.z, -1, 1e-12);
    ray out = {v3(0.6, 0.6, 2), v3(0, 0, -1), 0}; /* u + v > 1 */
    CHECK(!shape_hit(&t, &out, HIT_EPS, DBL_MAX, &h));
    ray neg = {v3(-0.1, 0.5, 2), v3(0, 0, -1), 0};
    CHECK(!shape_hit(&t, &neg, HIT_EPS, DBL_MAX, &h));
    ray flat = {v3(-1, 0.2, 0), v3(1, 0, 0), 0}; /* in the triangle's plane */
    CHECK(!shape_hit(&t, &flat, HIT_EPS, DBL_MAX, &h));
}

static void test_moving_sphere(void)
{
    struct hit h;
    struct prim m = {.type = PRIM_MOVING_SPHERE};
    m.g.msphere.center0 = v3(0, 0, 0);
    m.g.msphere.velocity = v3(10, 0, 0);
    m.g.msphere.radius = 1;
    m.g.msphere.time_lo = 0, m.g.msphere.time_hi = 1;
    ray at0 = {v3(0, 0, 5), v3(0, 0, -1), 0}, at1 = {v3(10, 0, 5), v3(0, 0, -1), 1};
    ray at1_early = {v3(10, 0, 5), v3(0, 0, -1), 0.5};
    CHECK(shape_hit(&m, &at0, HIT_EPS, DBL_MAX, &h));
    CHECK(shape_hit(&m, &at1, HIT_EPS, DBL_MAX, &h));
    CHECK(!shape_hit(&m, &at1_early, HIT_EPS, DBL_MAX, &h));
    vec3 lo, hi;
    shape_bounds(&m, &lo, &hi);
    CHECK(lo.x <= -1 && hi.x >= 11 && lo.y <= -1 && hi.y >= 1);
}

/* Along a diameter of a medium sphere, the chance of scattering is 1 - exp(-density * 2R). */
static void test_medium(void)
{
    struct prim m = {.type = PRIM_MEDIUM};
    m.g.medium.center = v3(0, 0, 0);
    m.g.medium.radius = 1;
    m.g.medium.neg_inv_density = -1 / 0.5;
    shape_prepare(&m);
    struct rng g;
    rng_seed(&g, 5, 5);
    struct hit h;
    int hits = 0, inside = 1;
    const int n = 40000;
    double tsum = 0;
    for (int i = 0; i < n; i++) {
        double z = 3 + rng_uniform(&g);
        ray r = {v3(0, 0, z), v3(0, 0, -1), rng_uniform(&g)};
        if (shape_hit(&m, &r, HIT_EPS, DBL_MAX, &h)) {
            hits++;
            inside &= fabs(h.p.z) <= 1 + 1e-9;
            tsum += h.t - (z - 1);
        }
    }
    CHECK(inside);
    CHECK_NEAR((double)hits / n, 1 - exp(-0.5 * 2), 0.01);
    /* Mean depth of the first scattering given one: truncated exponential on [0, 2]. */
    double lam = 0.5, L = 2, mean = 1 / lam - L * exp(-lam * L) / (1 - exp(-lam * L));
    CHECK_NEAR(tsum / hits, mean, 0.02);
    /* Pure: the same ray always gets the same answer. */
    ray r = {v3(0.1, 0.2, 3), v3(0, 0, -1), 0.25};
    int a = shape_hit(&m, &r, HIT_EPS, DBL_MAX, &h);
    double ta = h.t;
    int same = 1;
    for (int i = 0; i < 10; i++) {
        struct hit h2;
        int b = shape_hit(&m, &r, HIT_EPS, DBL_MAX, &h2);
        same &= a == b && (!a || h2.t == ta);
    }
    CHECK(same);
    /* Every word of the ray feeds the free-flight draw: rays that differ in one word by a
       relative 1e-12 (the same geometry to 1e-9) scatter at unrelated depths, not the same one. */
    int related[7] = {0}, tried = 0;
    for (int i = 0; i < 2000; i++) {
        ray b = {v3(0.3 * rng_uniform(&g), 0.3 * rng_uniform(&g), 3),
                 v3(0.01 * rng_uniform(&g), 0.01, -1 - rng_uniform(&g)), rng_uniform(&g)};
        struct hit hb;
        if (!shape_hit(&m, &b, HIT_EPS, DBL_MAX, &hb))
            continue;
        tried++;
        for (int w = 0; w < 7; w++) {
            ray c = b;
            double *word[7] = {&c.orig.x, &c.orig.y, &c.orig.z, &c.dir.x, &c.dir.y, &c.dir.z, &c.time};
            *word[w] = *word[w] == 0 ? 1e-300 : *word[w] * (1 + 1e-12);
            struct hit hc;
            related[w] += shape_hit(&m, &c, HIT_EPS, DBL_MAX, &hc) && fabs(hc.t - hb.t) < 1e-6;
        }
    }
    CHECK(tried > 500);
    for (int w = 0; w < 7; w++)
        CHECK(related[w] < tried / 20);
    /* The flight's uniform: the ray's words and the medium's radius and density (the key
       shape_prepare derives), each times its odd constant, summed, then SplitMix64's finaliser. */
    uint64_t rad_bits, nid_bits;
    memcpy(&rad_bits, &m.g.medium.radius, sizeof rad_bits);
    memcpy(&nid_bits, &m.g.medium.neg_inv_density, sizeof nid_bits);
    const uint64_t key = rad_bits * 0x5851f42d4c957f2dULL + nid_bits * 0xda942042e4dd58b5ULL;
    int as_defined = 1;
    for (int i = 0; i < 100; i++) {
        ray b = {v3(rng_uniform(&g), rng_uniform(&g), 3), v3(rng_uniform(&g), 0.1, -1), rng_uniform(&g)};
        struct medium_flight f;
        shape_medium_flight(&m, &b, shape_ray_hash(&b), &f);
        as_defined &= f.u == (double)((rng_mix64(shape_ray_hash(&b) + key) >> 11) + 1) * 0x1.0p-53;
    }
    CHECK(as_defined);
}

/* The book's constant medium with this medium's flight: both roots, the span inside (t_min,
   t_max), the flight by the log, no bounds; shape_medium_hit must give the same answer and t. */
static int book_medium(const struct prim *p, const ray *r, double t_min, double t_max, double *t)
{
    struct medium_flight f;
    shape_medium_flight(p, r, shape_ray_hash(r), &f);
    vec3 oc = v3_sub(r->orig, p->g.medium.center);
    double a = v3_len2(r->dir), half_b = v3_dot(oc, r->dir);
    double disc = half_b * half_b - a * (v3_len2(oc) - p->g.medium.radius * p->g.medium.radius);
    if (disc < 0 || a == 0)
        return 0;
    double sq = sqrt(disc), inv_a = 1 / a, t0 = (-half_b - sq) * inv_a, t1 = (-half_b + sq) * inv_a;
    double enter = t0 > t_min ? t0 : t_min, leave = t1 < t_max ? t1 : t_max;
    if (!(enter < leave))
        return 0;
    double span = (leave - enter) * f.len, dist = p->g.medium.neg_inv_density * log(f.u);
    if (dist > span)
        return 0;
    *t = enter + dist / f.len;
    return 1;
}

/* shape_medium_hit's early outs change no answer: random rays from inside and outside media of
   thin to dense fog, long and short directions, spans cut by t_max or not. */
static void test_medium_as_book(void)
{
    struct rng g;
    rng_seed(&g, 8, 8);
    int same = 1, hits = 0, misses = 0;
    for (int i = 0; i < 200000; i++) {
        struct prim m = {.type = PRIM_MEDIUM};
        m.g.medium.center = v3(rng_uniform(&g) * 4 - 2, rng_uniform(&g) * 4 - 2, rng_uniform(&g) * 4 - 2);
        m.g.medium.radius = 0.5 + 3 * rng_uniform(&g);
        m.g.medium.neg_inv_density = -exp(6 * rng_uniform(&g) - 3) * m.g.medium.radius;
        shape_prepare(&m);
        double scale = exp(4 * rng_uniform(&g) - 2);
        ray r = {v3(rng_uniform(&g) * 8 - 4, rng_uniform(&g) * 8 - 4, rng_uniform(&g) * 8 - 4),
                 v3_scale(v3(rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5), scale),
                 rng_uniform(&g)};
        double t_min = i % 5 == 0 ? 0 : HIT_EPS, t_max = i % 3 ? DBL_MAX : 10 * rng_uniform(&g) / scale;
        double tb = 0;
        struct hit h;
        int b = book_medium(&m, &r, t_min, t_max, &tb), s = shape_hit(&m, &r, t_min, t_max, &h);
        same &= b == s && (!b || h.t == tb);
        hits += b;
        misses += !b;
    }
    CHECK(same);
    CHECK(hits > 10000 && misses > 100000);
}

/* Light sampling of p from o: every sampled direction hits p with a positive pdf, the mean of
   1/pdf over sampled directions is the solid angle p covers, the pdf integrates to 1 over the
   sphere of directions, and the sampled directions are spread as the pdf says: the mean of
   g(d) = 1 - cos(d, toward c) over samples equals its integral against the pdf (the integrals
   estimated independently with uniform directions). */
static void check_light_pdf(const struct prim *p, vec3 o, vec3 c, const char *what)
{
    vec3 to_c = v3_unit(v3_sub(c, o));
    double g_sampled = 0, g_uniform = 0;
    struct rng g;
    rng_seed(&g, 11, 11);
    const int n = 200000;
    double inv_sum = 0, pdf_sum = 0;
    int all_hit = 1, covered = 0;
    struct hit h;
    int sample_same = 1;
    for (int i = 0; i < n; i++) {
        struct pt2 sp = {rng_uniform(&g), rng_uniform(&g)};
        double pdf_sample;
        /* light_sample: a unit direction (a sphere's cone direction is one by construction, to
           rounding, and is not normalised again), its density light_pdf's up to rounding */
        vec3 d = light_sample(p, o, sp, &pdf_sample);
        double pdf = light_pdf(p, o, d);
        sample_same &= fabs(v3_len2(d) - 1) < 1e-14 && fabs(pdf_sample - pdf) <= 1e-9 * pdf;
        ray r = {o, d, 0};
        all_hit &= pdf > 0 && shape_hit(p, &r, 1e-9, DBL_MAX, &h);
        inv_sum += pdf > 0 ? 1 / pdf : 0;
        g_sampled += 1 - v3_dot(v3_unit(d), to_c);
        double z = 1 - 2 * rng_uniform(&g), phi = 2 * PI * rng_uniform(&g), s = sqrt(1 - z * z);
        vec3 u = v3(cos(phi) * s, sin(phi) * s, z);
        ray ru = {o, u, 0};
        covered += shape_hit(p, &ru, 1e-9, DBL_MAX, &h);
        double pu = light_pdf(p, o, u);
        pdf_sum += pu;
        g_uniform += (1 - v3_dot(u, to_c)) * pu;
    }
    double omega = 4 * PI * covered / n;
    if (!all_hit)
        printf("%s: a sampled direction missed the light\n", what);
    CHECK(all_hit);
    if (!sample_same)
        printf("%s: light_sample differs from light_pdf\n", what);
    CHECK(sample_same);
    CHECK_NEAR(inv_sum / n / omega, 1, 0.03);
    CHECK_NEAR(pdf_sum / n * 4 * PI, 1, 0.03);
    CHECK_NEAR(g_uniform / n * 4 * PI / (g_sampled / n), 1, 0.05);
}

static void test_light_pdfs(void)
{
    struct prim s = {.type = PRIM_SPHERE};
    s.g.sphere.center = v3(0, 0, -4);
    s.g.sphere.radius = 1.5;
    check_light_pdf(&s, v3(0, 0, 0), s.g.sphere.center, "sphere from outside");
    check_light_pdf(&s, v3(0.5, 0.2, -4), v3(0, 0, 10), "sphere from inside");
    /* A tiny far sphere: 1 - cos(theta_max) ~ 1e-14 must not round to 0. */
    struct prim far = s;
    far.g.sphere.center = v3(0, 0, -1e7);
    far.g.sphere.radius = 1;
    double pdf = light_pdf(&far, v3(0, 0, 0), v3(0, 0, -1));
    CHECK(isfinite(pdf) && pdf > 0);
    CHECK_NEAR(pdf * PI * 1e-14, 1, 1e-6); /* 1 / (2 pi (1 - cos)) with 1 - cos = r^2 / 2d^2 */

    struct prim q = {.type = PRIM_RECT};
    q.g.rect.axis = 1;
    q.g.rect.a0 = -1, q.g.rect.a1 = 2, q.g.rect.b0 = -1, q.g.rect.b1 = 1, q.g.rect.k = 3;
    shape_prepare(&q);
    check_light_pdf(&q, v3(0.3, 0, 0.2), v3(0.5, 3, 0), "rect");
    struct prim dk = {.type = PRIM_DISK};
    dk.g.disk.center = v3(1, 2, 0);
    dk.g.disk.radius = 1.2;
    onb f = onb_from_w(v3_unit(v3(-1, -2, 0.5)));
    dk.g.disk.normal = f.w, dk.g.disk.e1 = f.u, dk.g.disk.e2 = f.v;
    shape_prepare(&dk);
    check_light_pdf(&dk, v3(0, 0, 0), dk.g.disk.center, "disk");
    /* given cos and sin of 2 pi s.y, a disk or rect samples as without them, up to rounding */
    struct rng g;
    rng_seed(&g, 4, 4);
    double worst = 0;
    for (int i = 0; i < 100000; i++) {
        struct pt2 sp = {rng_uniform(&g), rng_uniform(&g)};
        double sn, cs, pdf_plain, pdf_turn;
        v3_sincos_turn(sp.y, &sn, &cs);
        const struct prim *lp = i % 2 ? &dk : &q;
        vec3 o = v3(4 * rng_uniform(&g) - 2, 4 * rng_uniform(&g) - 2, 4 * rng_uniform(&g) - 2);
        vec3 d = light_sample(lp, o, sp, &pdf_plain), dt = light_sample_turn(lp, o, sp, cs, sn, &pdf_turn);
        worst = fmax(worst, v3_len(v3_sub(d, dt)));
        worst = fmax(worst, fabs(pdf_plain - pdf_turn) / (pdf_plain + 1e-300));
    }
    CHECK(worst < 1e-12);
    CHECK(shape_light_uses_points(&q) && shape_light_uses_points(&dk) && !shape_light_uses_points(&s));
}

/* One case of a planar light's pre-test check: a direction from o toward `at` (scaled by a random
   power of two) or, every third case, anywhere; the pdf through light_pdf (pre-test, then
   the plane hit) must equal the plane hit's alone (hit: shape_light_inline.h's disk_pdf_hit or
   rect_pdf_hit), bit for bit, and be positive exactly where shape_hit hits. */
static void check_pretest_case(const struct prim *p, vec3 o, vec3 at, int i, struct rng *g,
                               double (*hit)(const struct prim *, vec3, vec3), int *same, int *hits)
{
    vec3 dir = v3_scale(v3_sub(at, o), ldexp(1, (int)(10 * rng_uniform(g)) - 15));
    if (i % 3 == 2)
        dir = v3(2 * rng_uniform(g) - 1, 2 * rng_uniform(g) - 1, 2 * rng_uniform(g) - 1);
    double want = hit(p, o, dir), got = light_pdf(p, o, dir);
    *hits += want > 0;
    *same &= memcmp(&want, &got, sizeof want) == 0;
    /* the pdf's plane test is shape_hit's (rect_plane, disk_plane): a positive pdf where the ray
       hits, 0 where it misses (or grazes: planar_pdf's 0 within 1e-12 of the plane) */
    struct hit h;
    const ray r = {o, dir, 0};
    const int hit_ok = shape_hit(p, &r, HIT_EPS, DBL_MAX, &h);
    const vec3 n = p->type == PRIM_DISK ? p->g.disk.normal : p->g.rect.n;
    *same &= want > 0 ? hit_ok : !hit_ok || planar_pdf(p, h.t, v3_dot(dir, n), dir) == 0;
}

/* The pre-test only rejects directions the exact test rejects: the same value, bit for bit, for
   directions aimed at the rim (just inside and outside it), at the disk and anywhere, from
   origins far, near, inside the bounding ball and in the disk's plane, and directions of any
   length. */
static void test_disk_pdf_pretest(void)
{
    struct prim dk = {.type = PRIM_DISK};
    dk.g.disk.center = v3(278, 554, 279);
    dk.g.disk.radius = 60;
    onb f = onb_from_w(v3_unit(v3(0.1, -1, 0.2)));
    dk.g.disk.normal = f.w, dk.g.disk.e1 = f.u, dk.g.disk.e2 = f.v;
    shape_prepare(&dk);
    struct rng g;
    rng_seed(&g, 5, 5);
    int same = 1, hits = 0, n = 400000;
    for (int i = 0; i < n; i++) {
        double scale = (i % 4 == 0 ? 2 : i % 4 == 1 ? 200 : i % 4 == 2 ? 1000 : 1e5) * rng_uniform(&g);
        vec3 o =
            v3_add(dk.g.disk.center, v3(scale * (2 * rng_uniform(&g) - 1), scale * (2 * rng_uniform(&g) - 1),
                                        scale * (2 * rng_uniform(&g) - 1)));
        if (i % 16 == 5) /* in the disk's plane */
            o = v3_fma(o, dk.g.disk.normal, -v3_dot(v3_sub(o, dk.g.disk.center), dk.g.disk.normal));
        double sin_a, cos_a, rim = dk.g.disk.radius;
        v3_sincos_turn(rng_uniform(&g), &sin_a, &cos_a);
        switch (i % 3) {
        case 0: /* at the rim, within a few ulps to 1e-6 */
            rim *= 1 + ldexp(2 * rng_uniform(&g) - 1, -(int)(20 + 33 * rng_uniform(&g)));
            break;
        case 1:
            rim *= 1.2 * rng_uniform(&g);
            break;
        }
        vec3 q = v3_add(dk.g.disk.center,
                        v3_add(v3_scale(dk.g.disk.e1, rim * cos_a), v3_scale(dk.g.disk.e2, rim * sin_a)));
        check_pretest_case(&dk, o, q, i, &g, disk_pdf_hit, &same, &hits);
    }
    CHECK(same);
    CHECK(hits > n / 5);
}

/* As for the disk: the rect's pre-test (the cone of the ball about its centre through its
   corners) only rejects directions the plane hit rejects, bit for bit, for directions aimed at
   its corners and edges (just inside and outside), at it and anywhere, from origins far, near,
   inside the ball and in its plane, for each normal axis. */
static void test_rect_pdf_pretest(void)
{
    struct rng g;
    rng_seed(&g, 7, 7);
    int same = 1, hits = 0, n = 300000;
    for (int i = 0; i < n; i++) {
        struct prim q = {.type = PRIM_RECT};
        q.g.rect.axis = i % 3;
        q.g.rect.a0 = 213, q.g.rect.a1 = 343, q.g.rect.b0 = 227, q.g.rect.b1 = 332, q.g.rect.k = 554;
        if (i % 5 == 4) /* thin */
            q.g.rect.a0 = -0.5, q.g.rect.a1 = 0.25, q.g.rect.b0 = 1e-3, q.g.rect.b1 = 300;
        shape_prepare(&q);
        double ca = 0.5 * (q.g.rect.a0 + q.g.rect.a1), cb = 0.5 * (q.g.rect.b0 + q.g.rect.b1);
        vec3 c = v3_add(v3_add(v3_scale(q.g.rect.n, q.g.rect.k), v3_scale(q.g.rect.ea, ca)),
                        v3_scale(q.g.rect.eb, cb));
        double scale = (i % 4 == 0 ? 2 : i % 4 == 1 ? 200 : i % 4 == 2 ? 1000 : 1e5) * rng_uniform(&g);
        vec3 o = v3_add(c, v3(scale * (2 * rng_uniform(&g) - 1), scale * (2 * rng_uniform(&g) - 1),
                              scale * (2 * rng_uniform(&g) - 1)));
        if (i % 16 == 5) /* in the rect's plane */
            o = v3_fma(o, q.g.rect.n, q.g.rect.k - v3_dot(o, q.g.rect.n));
        double pa = q.g.rect.a0 + rng_uniform(&g) * (q.g.rect.a1 - q.g.rect.a0);
        double pb = q.g.rect.b0 + rng_uniform(&g) * (q.g.rect.b1 - q.g.rect.b0);
        if (i % 3 == 0) { /* at an edge or a corner, within a few ulps to 1e-6 */
            double nudge = 1 + ldexp(2 * rng_uniform(&g) - 1, -(int)(20 + 33 * rng_uniform(&g)));
            if (i % 2)
                pa = (rng_uniform(&g) < 0.5 ? q.g.rect.a0 : q.g.rect.a1) * nudge;
            if (i % 7 < 4)
                pb = (rng_uniform(&g) < 0.5 ? q.g.rect.b0 : q.g.rect.b1) * nudge;
        }
        vec3 at = v3_add(v3_add(v3_scale(q.g.rect.n, q.g.rect.k), v3_scale(q.g.rect.ea, pa)),
                         v3_scale(q.g.rect.eb, pb));
        check_pretest_case(&q, o, at, i, &g, rect_pdf_hit, &same, &hits);
    }
    CHECK(same);
    CHECK(hits > n / 5);
}

/* A sphere light's pdf as it was before its cone test folded the sign into dc |dc|: dc > 0 and
   dc^2 >= (d2 - r2) |dir|^2, then the cone's density. */
static double sphere_pdf_two_tests(const struct prim *p, vec3 o, vec3 dir)
{
    vec3 to_c = v3_sub(p->g.sphere.center, o);
    double d2 = v3_len2(to_c), r2 = p->g.sphere.radius * p->g.sphere.radius;
    if (d2 <= r2)
        return 1 / (4 * PI);
    double dc = v3_dot(dir, to_c);
    if (!(dc > 0 && dc * dc >= (d2 - r2) * v3_len2(dir)))
        return 0;
    double s2 = r2 / d2;
    return 1 / (2 * PI * (s2 / (1 + sqrt(1 - s2))));
}

/* The sphere's one-branch cone test gives the two tests' pdf bit for bit: directions at the
   cone's rim (a few ulps to 1e-6 off a tangent), square to the axis (dc ~ 0, both signs), away
   from the sphere, from near, far and inside, over scales of direction. */
static void test_sphere_pdf_cone(void)
{
    struct rng g;
    rng_seed(&g, 9, 9);
    int same = 1, hits = 0, misses_behind = 0, n = 300000;
    struct prim b = {.type = PRIM_SPHERE};
    b.g.sphere.center = v3(190, 90, 190), b.g.sphere.radius = 90;
    shape_prepare(&b);
    for (int i = 0; i < n; i++) {
        double scale = (i % 4 == 0 ? 95 : i % 4 == 1 ? 300 : i % 4 == 2 ? 3000 : 1e6) * rng_uniform(&g);
        vec3 o =
            v3_add(b.g.sphere.center, v3(scale * (2 * rng_uniform(&g) - 1), scale * (2 * rng_uniform(&g) - 1),
                                         scale * (2 * rng_uniform(&g) - 1)));
        vec3 to_c = v3_sub(b.g.sphere.center, o), w = v3_unit(to_c);
        vec3 side = v3_unit(v3_cross(w, fabs(w.x) < 0.5 ? v3(1, 0, 0) : v3(0, 1, 0)));
        double d = v3_len(to_c), sin_max = d > 90 ? 90 / d : 1,
               cos_max = sqrt(fmax(0, 1 - sin_max * sin_max));
        vec3 dir;
        if (i % 3 == 0) { /* at the rim */
            double nudge = 1 + ldexp(2 * rng_uniform(&g) - 1, -(int)(20 + 33 * rng_uniform(&g)));
            dir = v3_add(v3_scale(w, cos_max * nudge), v3_scale(side, sin_max));
        } else if (i % 3 == 1) { /* square to the axis, either side */
            dir = v3_add(v3_scale(w, ldexp(2 * rng_uniform(&g) - 1, -(int)(60 * rng_uniform(&g)))), side);
        } else {
            dir = v3(2 * rng_uniform(&g) - 1, 2 * rng_uniform(&g) - 1, 2 * rng_uniform(&g) - 1);
        }
        dir = v3_scale(dir, ldexp(1, (int)(10 * rng_uniform(&g)) - 5));
        double want = sphere_pdf_two_tests(&b, o, dir), got = light_pdf(&b, o, dir);
        hits += want > 0;
        misses_behind += want == 0 && v3_dot(dir, to_c) <= 0;
        same &= memcmp(&want, &got, sizeof want) == 0;
    }
    CHECK(same);
    CHECK(hits > n / 10);
    CHECK(misses_behind > n / 10);
}

/* shape_lights_pdf is the mean of the lights' own pdfs, summed in index order with the known
   light's given pdf in its place, bit for bit, whether or not a direction enters a disk's cone
   (the disks' exact tests run out of the loop from the first disk the direction may hit);
   shape_prepare fills a disk's r2 and r2_out. */
static void test_lights_pdf_sum(void)
{
    struct scene *sc = scene_new();
    CHECK(sc != NULL);
    if (!sc)
        return;
    vec3 centers[3] = {v3(278, 554, 279), v3(500, 500, 500), v3(60, 500, 500)};
    for (int k = 0; k < 3; k++) {
        struct prim dk = {.type = PRIM_DISK};
        dk.g.disk.center = centers[k];
        dk.g.disk.radius = 60;
        onb f = onb_from_w(v3_unit(v3_sub(v3(278, 0, 279), centers[k])));
        dk.g.disk.normal = f.w, dk.g.disk.e1 = f.u, dk.g.disk.e2 = f.v;
        int at = scene_add_prim(sc, &dk);
        CHECK(at >= 0 && scene_add_light(sc, at) >= 0);
        if (k == 1) { /* a rect and a sphere between the disks */
            struct prim q = {.type = PRIM_RECT}, b = {.type = PRIM_SPHERE};
            q.g.rect.axis = 1;
            q.g.rect.a0 = 213, q.g.rect.a1 = 343, q.g.rect.b0 = 227, q.g.rect.b1 = 332, q.g.rect.k = 554;
            b.g.sphere.center = v3(190, 90, 190), b.g.sphere.radius = 90;
            int qi = scene_add_prim(sc, &q), bi = scene_add_prim(sc, &b);
            CHECK(qi >= 0 && scene_add_light(sc, qi) >= 0 && bi >= 0 && scene_add_light(sc, bi) >= 0);
        }
    }
    const struct prim *d0 = &sc->prims[sc->lights[0]];
    CHECK(d0->g.disk.r2 == 60.0 * 60.0 && d0->g.disk.r2_out == 3600 * (1 + 1e-6));
    struct rng g;
    rng_seed(&g, 6, 6);
    int same = 1, inside = 0, n = 200000;
    for (int i = 0; i < n; i++) {
        vec3 o = v3(555 * rng_uniform(&g), 555 * rng_uniform(&g), 555 * rng_uniform(&g));
        int aim = (int)rng_below(&g, (uint32_t)sc->n_lights + 1),
            known = (int)rng_below(&g, (uint32_t)sc->n_lights + 1);
        if (known == sc->n_lights)
            known = -1;
        vec3 dir;
        if (aim < sc->n_lights) { /* toward a light's point, or its sphere's centre */
            const struct prim *lp = &sc->prims[sc->lights[aim]];
            struct pt2 sp = {rng_uniform(&g), rng_uniform(&g)};
            dir = v3_unit(lp->type == PRIM_SPHERE ? v3_sub(lp->g.sphere.center, o)
                                                  : v3_sub(light_point(lp, sp), o));
        } else {
            dir = v3_unit(v3(2 * rng_uniform(&g) - 1, 2 * rng_uniform(&g) - 1, 2 * rng_uniform(&g) - 1));
        }
        double known_pdf = 0.25 + rng_uniform(&g), sum = 0;
        for (int k = 0; k < sc->n_lights; k++) {
            double one = k == known ? known_pdf : light_pdf(&sc->prims[sc->lights[k]], o, dir);
            inside += k != known && one > 0 && sc->prims[sc->lights[k]].type == PRIM_DISK;
            sum += one;
        }
        double want = sum / sc->n_lights, got = shape_lights_pdf(sc, o, dir, known, known_pdf);
        same &= memcmp(&want, &got, sizeof want) == 0;
    }
    CHECK(same);
    CHECK(inside > n / 20);
    scene_free(sc);
}

/* shape_lights_pdf over one, two and three lights (a rect, then a sphere, then a disk) is the
   in-order sum of the lights' pdfs divided by their count, bit for bit (one or two lights take
   no division); and a sphere light's sampled direction is a unit vector to rounding. */
static void test_lights_pdf_mean(void)
{
    struct scene *sc = scene_new();
    CHECK(sc != NULL);
    if (!sc)
        return;
    struct prim q = {.type = PRIM_RECT}, b = {.type = PRIM_SPHERE}, dk = {.type = PRIM_DISK};
    q.g.rect.axis = 1;
    q.g.rect.a0 = 213, q.g.rect.a1 = 343, q.g.rect.b0 = 227, q.g.rect.b1 = 332, q.g.rect.k = 554;
    b.g.sphere.center = v3(190, 90, 190), b.g.sphere.radius = 90;
    dk.g.disk.center = v3(400, 500, 300), dk.g.disk.radius = 50;
    onb f = onb_from_w(v3(0, -1, 0));
    dk.g.disk.normal = f.w, dk.g.disk.e1 = f.u, dk.g.disk.e2 = f.v;
    const struct prim *add[3] = {&q, &b, &dk};
    struct rng g;
    rng_seed(&g, 8, 8);
    int same = 1, unit = 1, positive = 0;
    for (int lights = 1; lights <= 3; lights++) {
        int at = scene_add_prim(sc, add[lights - 1]);
        CHECK(at >= 0 && scene_add_light(sc, at) >= 0);
        for (int i = 0; i < 50000; i++) {
            vec3 o = v3(555 * rng_uniform(&g), 555 * rng_uniform(&g), 555 * rng_uniform(&g));
            int known = (int)rng_below(&g, (uint32_t)lights + 1) - 1;
            const struct prim *aim = &sc->prims[sc->lights[rng_below(&g, (uint32_t)lights)]];
            double pdf;
            struct pt2 sp = {rng_uniform(&g), rng_uniform(&g)};
            vec3 dir = light_sample(aim, o, sp, &pdf);
            if (aim->type == PRIM_SPHERE)
                unit &= fabs(v3_len2(dir) - 1) < 1e-14;
            double known_pdf = 0.25 + rng_uniform(&g), sum = 0;
            for (int k = 0; k < lights; k++)
                sum += k == known ? known_pdf : light_pdf(&sc->prims[sc->lights[k]], o, dir);
            double want = sum / lights, got = shape_lights_pdf(sc, o, dir, known, known_pdf);
            positive += got > 0;
            same &= memcmp(&want, &got, sizeof want) == 0;
        }
    }
    CHECK(same);
    CHECK(unit);
    CHECK(positive > 100000);
    scene_free(sc);
}

/* Hits of random rays land inside the primitive's bounds, transformed or not. */
static void test_bounds(void)
{
    struct prim ps[4] = {
        {.type = PRIM_BOX}, {.type = PRIM_CYLINDER}, {.type = PRIM_TRIANGLE}, {.type = PRIM_SPHERE}};
    ps[0].g.box.lo = v3(-1, 0, -2), ps[0].g.box.hi = v3(1, 3, 2);
    ps[1].g.cyl.base = v3(0, 0, 0), ps[1].g.cyl.axis = v3_unit(v3(1, 2, -1)), ps[1].g.cyl.height = 3;
    ps[1].g.cyl.radius = 0.7;
    ps[2].g.tri.v0 = v3(0, 0, 0), ps[2].g.tri.e1 = v3(2, 1, 0), ps[2].g.tri.e2 = v3(0, 1, 2);
    ps[2].g.tri.normal = v3_unit(v3_cross(ps[2].g.tri.e1, ps[2].g.tri.e2));
    ps[3].g.sphere.center = v3(1, 1, 1), ps[3].g.sphere.radius = 1.5;
    struct rng g;
    rng_seed(&g, 2, 2);
    int inside = 1, hits = 0;
    for (int k = 0; k < 8; k++) {
        struct prim p = ps[k % 4];
        if (k >= 4)
            set_xform(&p, -18 + 31 * k, v3(160, 230, 80));
        vec3 lo, hi;
        shape_bounds(&p, &lo, &hi);
        vec3 c = v3_scale(v3_add(lo, hi), 0.5);
        for (int i = 0; i < 2000; i++) {
            vec3 o = v3_add(
                c, v3(20 * rng_uniform(&g) - 10, 20 * rng_uniform(&g) - 10, 20 * rng_uniform(&g) - 10));
            vec3 target = v3_add(
                c, v3(3 * rng_uniform(&g) - 1.5, 3 * rng_uniform(&g) - 1.5, 3 * rng_uniform(&g) - 1.5));
            ray r = {o, v3_sub(target, o), 0};
            struct hit h;
            if (!shape_hit(&p, &r, HIT_EPS, DBL_MAX, &h))
                continue;
            hits++;
            inside &= h.p.x >= lo.x - 1e-9 && h.p.x <= hi.x + 1e-9 && h.p.y >= lo.y - 1e-9 &&
                      h.p.y <= hi.y + 1e-9 && h.p.z >= lo.z - 1e-9 && h.p.z <= hi.z + 1e-9;
            inside &= fabs(v3_len(h.n) - 1) < 1e-9 && v3_dot(h.n, r.dir) <= 0;
        }
    }
    CHECK(inside);
    CHECK(hits > 4000);
}

int main(void)
{
    test_box();
    test_box_as_book();
    test_box_xform();
    test_cylinder();
    test_triangle();
    test_moving_sphere();
    test_medium();
    test_medium_as_book();
    test_light_pdfs();
    test_disk_pdf_pretest();
    test_rect_pdf_pretest();
    test_sphere_pdf_cone();
    test_lights_pdf_sum();
    test_lights_pdf_mean();
    test_bounds();
    return check_report("test_shape");
}
