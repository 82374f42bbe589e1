/* Tests for Perlin noise, the marble and image textures, and the sphere's (u, v) map. */
#include <stdlib.h>

#include "check.h"
#include "shape.h"
#include "texture.h"

static void test_perlin(void)
{
    static struct perlin a, b, c;
    perlin_init(&a, 1);
    perlin_init(&b, 1);
    perlin_init(&c, 2);
    int same = 1, differ = 0, bounded = 1, smooth = 1;
    double lo = 1, hi = -1;
    struct rng g;
    rng_seed(&g, 4, 4);
    for (int i = 0; i < 5000; i++) {
        vec3 p = v3(40 * rng_uniform(&g) - 20, 40 * rng_uniform(&g) - 20, 40 * rng_uniform(&g) - 20);
        double na = perlin_noise(&a, p);
        same &= na == perlin_noise(&b, p);
        differ += fabs(na - perlin_noise(&c, p)) > 1e-3;
        bounded &= fabs(na) <= 1.0;
        lo = na < lo ? na : lo;
        hi = na > hi ? na : hi;
        /* Gradient noise is continuous: a tiny step moves it a tiny amount. */
        smooth &= fabs(perlin_noise(&a, v3_add(p, v3(1e-6, 1e-6, 1e-6))) - na) < 1e-4;
        double t = perlin_turb(&a, p, 7);
        bounded &= t >= 0 && t <= 2;
    }
    CHECK(same);
    CHECK(differ > 4000);
    CHECK(bounded);
    CHECK(smooth);
    CHECK(lo < -0.3 && hi > 0.3); /* it actually varies */
    /* Zero at lattice points (the gradient's dot with a zero offset), as Perlin's noise is. */
    CHECK_NEAR(perlin_noise(&a, v3(3, -7, 12)), 0, 1e-12);
    CHECK(perlin_noise(&a, v3(NAN, 0, 0)) == 0);
    CHECK(isfinite(perlin_noise(&a, v3(1e300, -1e300, 5))));
}

static void test_textures(void)
{
    struct scene *sc = scene_new();
    CHECK(sc && scene_use_perlin(sc) == 0);
    /* A 2x2 image: red, green on the top row; blue, white below. */
    struct rgb8 img;
    struct err e;
    CHECK(rgb8_alloc(&img, 2, 2, &e) == 0);
    const uint8_t px[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    for (int i = 0; i < 12; i++)
        img.px[i] = px[i];
    int idx = scene_add_image(sc, &img);
    CHECK(idx == 0 && img.px == NULL);
    struct texture im = {.type = TEX_IMAGE, .image = idx};
    struct texture noise = {.type = TEX_NOISE, .scale = 4};
    struct texture ck = {.type = TEX_CHECKER, .odd = v3(0, 0, 0), .even = v3(1, 1, 1), .scale = 1};
    CHECK(texture_needs_uv(&im) && !texture_needs_uv(&noise) && !texture_needs_uv(&ck));
    vec3 tl = texture_value(sc, &im, 0.1, 0.9, v3(0, 0, 0)); /* v = 1 is the top row */
    vec3 br = texture_value(sc, &im, 0.9, 0.1, v3(0, 0, 0));
    vec3 edge = texture_value(sc, &im, 1.0, 0.0, v3(0, 0, 0)); /* clamped, in bounds */
    vec3 out = texture_value(sc, &im, -3, 7, v3(0, 0, 0));
    CHECK(tl.x == 1 && tl.y == 0 && tl.z == 0);
    CHECK(br.x == 1 && br.y == 1 && br.z == 1);
    CHECK(edge.x == 1 && edge.y == 1);
    CHECK(out.x == 1 && out.y == 0);
    int grey = 1, in01 = 1;
    double vmin = 1, vmax = 0;
    for (int i = 0; i < 2000; i++) {
        vec3 p = v3(i * 0.37, i * 0.11, i * 0.23);
        vec3 m = texture_value(sc, &noise, 0, 0, p);
        grey &= m.x == m.y && m.y == m.z;
        in01 &= m.x >= 0 && m.x <= 1;
        vmin = m.x < vmin ? m.x : vmin;
        vmax = m.x > vmax ? m.x : vmax;
    }
    CHECK(grey && in01);
    CHECK(vmin < 0.1 && vmax > 0.9); /* the marble's dark and light veins both appear */
    vec3 m = texture_marble(sc->perlin, 4, v3(1, 2, 3));
    vec3 t = texture_value(sc, &noise, 0.3, 0.4, v3(1, 2, 3));
    CHECK(m.x == t.x);
    scene_free(sc);
}

/* The sphere's map as RTOW: +x -> (u, v) = (0.5, 0.5), +z -> u = 0.25, the +y pole -> v = 1. */
static void test_sphere_uv(void)
{
    struct prim s = {.type = PRIM_SPHERE};
    s.g.sphere.center = v3(1, 2, 3);
    s.g.sphere.radius = 2;
    struct hit h;
    h.p = v3(3, 2, 3);
    shape_uv(&s, &h);
    CHECK_NEAR(h.u, 0.5, 1e-12);
    CHECK_NEAR(h.v, 0.5, 1e-12);
    h.p = v3(1, 4, 3);
    shape_uv(&s, &h);
    CHECK_NEAR(h.v, 1, 1e-12);
    h.p = v3(1, 2, 5); /* +z: phi = atan2(-1, 0) + pi = pi/2 */
    shape_uv(&s, &h);
    CHECK_NEAR(h.u, 0.25, 1e-12);
    /* A translated sphere maps the same relative point to the same (u, v). */
    struct prim t = s;
    t.has_xform = 1, t.cos_y = 1, t.sin_y = 0, t.offset = v3(10, 0, 0);
    h.p = v3(11, 2, 5);
    shape_uv(&t, &h);
    CHECK_NEAR(h.u, 0.25, 1e-12);
}

int main(void)
{
    test_perlin();
    test_textures();
    test_sphere_uv();
    return check_report("test_texture");
}
