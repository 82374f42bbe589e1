/* Tests for Perlin noise, the marble and image textures, and the sphere's (u, v) map. */
#include <stdlib.h>

#include "check.h"
#include "geom/shape.h"
#include "geom/scene.h"
#include "geom/texture.h"

/* The book's noise as written (RTOW "The Next Week", ch. 5, with floor and & 255 cells):
   perlin_noise and perlin_turb must give it bit for bit, whatever they do to be fast. */
static double book_noise(const struct perlin *p, vec3 q)
{
    double fx = floor(q.x), fy = floor(q.y), fz = floor(q.z);
    double u = q.x - fx, v = q.y - fy, w = q.z - fz;
    int i = (int)((int64_t)fx & 255), j = (int)((int64_t)fy & 255), k = (int)((int64_t)fz & 255);
    double uu = u * u * (3 - 2 * u), vv = v * v * (3 - 2 * v), ww = w * w * (3 - 2 * w);
    double accum = 0;
    for (int di = 0; di < 2; di++)
        for (int dj = 0; dj < 2; dj++)
            for (int dk = 0; dk < 2; dk++) {
                vec3 g = p->ranvec[p->perm_x[(i + di) & 255] ^ p->perm_y[(j + dj) & 255] ^
                                   p->perm_z[(k + dk) & 255]];
                accum += (di ? uu : 1 - uu) * (dj ? vv : 1 - vv) * (dk ? ww : 1 - ww) *
                         v3_dot(g, v3(u - di, v - dj, w - dk));
            }
    return accum;
}

/* The book's turbulence: depth octaves of book_noise at 2^o q, weights 2^-o. */
static double book_turb(const struct perlin *p, vec3 q, int depth)
{
    double accum = 0, weight = 1;
    for (int o = 0; o < depth; o++, weight *= 0.5)
        accum += weight * book_noise(p, v3_scale(q, (double)(1 << o)));
    return fabs(accum);
}

/* perlin_turb derives every octave's cell from the first's: check it bit for bit against the
   book where that is delicate: coordinates on halves and quarters of a cell (an octave's offset
   exactly 1/2), tiny negatives (1 - |x| rounds), -1 and -0, large ones, every depth to 10. */
static void test_perlin_octaves(void)
{
    static struct perlin a;
    perlin_init(&a, 3);
    const double xs[] = {0,
                         -0.0,
                         0.5,
                         0.25,
                         0.75,
                         1.5,
                         -0.5,
                         -1,
                         -1.5,
                         -2.25,
                         1e-300,
                         -1e-300,
                         -0x1.0p-60,
                         -0.3,
                         0.3,
                         255.5,
                         256,
                         -256.125,
                         1e6 + 0.5,
                         -1e6 - 0.375,
                         0x1.0p31 + 0.5,
                         0x1.0p33,
                         -0x1.0p33,
                         0.9999999999999999,
                         -0.9999999999999999,
                         127.03125};
    const int n = (int)(sizeof xs / sizeof xs[0]);
    int as_book = 1;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            for (int depth = 0; depth <= 10; depth++) {
                vec3 q = v3(xs[i], xs[j], xs[(i + j + depth) % n]);
                as_book &= perlin_turb(&a, q, depth) == book_turb(&a, q, depth);
            }
    struct rng g;
    rng_seed(&g, 5, 5);
    for (int i = 0; i < 20000; i++) { /* multiples of 2^-6 in [-8, 8): halves at every octave */
        vec3 q = v3(((int)rng_below(&g, 1024) - 512) / 64.0, ((int)rng_below(&g, 1024) - 512) / 64.0,
                    ((int)rng_below(&g, 1024) - 512) / 64.0);
        as_book &= perlin_turb(&a, q, 7) == book_turb(&a, q, 7);
    }
    CHECK(as_book);
    CHECK(perlin_turb(&a, v3(NAN, 1, 2), 7) == 0 && perlin_turb(&a, v3(1, INFINITY, 2), 7) == 0);
    /* At lattice points and on cell faces every term is a zero of some sign: the book's sum
       starts from +0, so its noise is never -0, and perlin_noise must not be either. */
    int plus_zero = 1, zeros = 0;
    for (int x = -12; x < 12; x++)
        for (int y = -12; y < 12; y++)
            for (int z = -12; z < 12; z++) {
                double nz = perlin_noise(&a, v3(x, y, z)), b = book_noise(&a, v3(x, y, z));
                plus_zero &= nz == 0 && !signbit(nz) && !signbit(b);
                zeros++;
            }
    CHECK(plus_zero && zeros == 24 * 24 * 24);
}

static void test_perlin(void)
{
    static struct perlin a, b, c;
    perlin_init(&a, 1);
    perlin_init(&b, 1);
    perlin_init(&c, 2);
    int same = 1, differ = 0, bounded = 1, smooth = 1, as_book = 1;
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
        double book_t = 0, weight = 1;
        for (int o = 0; o < 7; o++, weight *= 0.5)
            book_t += weight * book_noise(&a, v3_scale(p, (double)(1 << o)));
        as_book &= na == book_noise(&a, p) && t == fabs(book_t);
    }
    CHECK(as_book);
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
    CHECK(image_alloc(&img, 2, 2, &e) == 0);
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

/* The checker picks odd exactly where the product of libm's sines is negative (away from its
   zeros, where a rounding of x / pi may differ). */
static void test_checker_sign(void)
{
    struct scene *sc = scene_new();
    struct texture ck = {.type = TEX_CHECKER, .odd = v3(0, 0, 0), .even = v3(1, 1, 1), .scale = 10};
    struct rng g;
    rng_seed(&g, 5, 5);
    int same = 1, odd = 0;
    for (int i = 0; i < 200000; i++) {
        double r = i < 100000 ? 5 : 2000;
        vec3 p =
            v3(r * (2 * rng_uniform(&g) - 1), r * (2 * rng_uniform(&g) - 1), r * (2 * rng_uniform(&g) - 1));
        double s = sin(10 * p.x) * sin(10 * p.y) * sin(10 * p.z);
        if (fabs(s) < 1e-9)
            continue;
        vec3 c = texture_value(sc, &ck, 0, 0, p);
        same &= (c.x == 0) == (s < 0);
        odd += c.x == 0;
    }
    CHECK(same);
    CHECK(odd > 90000 && odd < 110000);
    CHECK(texture_value(sc, &ck, 0, 0, v3(0, -1, -1)).x == 1); /* a zero factor: even */
    CHECK(texture_value(sc, &ck, 0, 0, v3(1e300, 1, 1)).x == (sin(1e301) * sin(10) * sin(10) < 0 ? 0 : 1));
    scene_free(sc);
}

int main(void)
{
    test_checker_sign();
    test_perlin();
    test_perlin_octaves();
    test_textures();
    test_sphere_uv();
    return check_report("test_texture");
}
