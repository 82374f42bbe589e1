/* Tests for the wide kernel's nearest hit (wide_scene_hit, eight float lanes): against bvh_hit
   (double) for rays at every prim's corners, edges and face centres, from the eye, along the axes
   and in random directions, then from their hits: the same prim, t and outward normal within
   float's rounding (a ray grazing the sphere: across its surface); where two prims meet (a ray
   aimed at an edge or corner) either of them, at the same distance. And which scenes the kernel takes
   (wide_usable). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "box_point.h"
#include "bvh.h"
#include "check.h"
#include "render.h"
#include "render_wide.h"
#include "rng.h"
#include "scene_load.h"
#include "shape.h"

struct tally {
    int rays, hits, ties, bad;
};

/* Whether ray q is one that float rounding may send to another prim (or past them all): aimed at
   an edge or corner, where a turn of its direction by 1e-5 changes bvh_hit's prim. */
static int ambiguous(const struct scene *sc, const ray *q, double t_min, int prim)
{
    const double len = v3_len(q->dir);
    for (int k = 0; k < 6; k++) {
        const double s = (k & 1 ? 1e-5 : -1e-5) * len;
        ray p = *q;
        p.dir = v3_add(p.dir, v3(k / 2 == 0 ? s : 0, k / 2 == 1 ? s : 0, k / 2 == 2 ? s : 0));
        struct hit h;
        if ((bvh_hit(sc, &p, t_min, DBL_MAX, &h) ? h.prim : -1) != prim)
            return 1;
    }
    return 0;
}

/* The lanes' rays q through wide_scene_hit and one by one through bvh_hit. */
static void compare(const struct scene *sc, const struct wide_scene *ws, const ray q[WIDE_LANES],
                    double t_min, struct tally *ty)
{
    double o[3 * WIDE_LANES], d[3 * WIDE_LANES], t[WIDE_LANES], n[3 * WIDE_LANES];
    int prim[WIDE_LANES];
    for (int i = 0; i < WIDE_LANES; i++) {
        const int a = i, b = WIDE_LANES + i, c = 2 * WIDE_LANES + i;
        o[a] = q[i].orig.x, o[b] = q[i].orig.y, o[c] = q[i].orig.z;
        d[a] = q[i].dir.x, d[b] = q[i].dir.y, d[c] = q[i].dir.z;
    }
    wide_scene_hit(ws, o, d, t_min, t, prim, n);
    for (int i = 0; i < WIDE_LANES; i++) {
        struct hit h;
        const int got = bvh_hit(sc, &q[i], t_min, DBL_MAX, &h);
        const double len = v3_len(q[i].dir);
        ty->rays++;
        ty->hits += got;
        /* the same place within float's rounding: a few ulps of the scene's 555 (t |d| in world
           units), more far out on the sphere (its quadratic's cancellation) */
        const double dist = fabs(t[i] - h.t) * len, tol = 2e-3 + 1e-5 * h.t * len;
        if (prim[i] != (got ? h.prim : -1) &&
            (ambiguous(sc, &q[i], t_min, got ? h.prim : -1) || (got && prim[i] >= 0 && dist <= tol) ||
             (got ? h.t : t[i]) * len < 2 * t_min * len + 1e-3)) {
            ty->ties++; /* where two prims meet or lie in one plane, or at t_min: either */
            continue;
        }
        if (!got && prim[i] < 0)
            continue;
        const vec3 out = h.front ? h.n : v3_neg(h.n), wn = v3(n[i], n[WIDE_LANES + i], n[2 * WIDE_LANES + i]);
        /* a ray grazing the sphere (its root's square root amplifies the rounding) may be off
           along the surface, not off it: the distance across the surface within tol */
        const double across = fabs((t[i] - h.t) * v3_dot(q[i].dir, h.n));
        if (got && prim[i] == h.prim && (dist <= tol || (across <= tol && dist <= 1)) &&
            v3_len(v3_sub(out, wn)) < 1e-2)
            continue;
        ty->bad++;
        if (ty->bad <= 5)
            fprintf(stderr, "lane %d: bvh %d prim %d t %.9g, wide prim %d t %.9g n (%g %g %g)\n", i, got,
                    got ? h.prim : -1, got ? h.t : 0, prim[i], t[i], wn.x, wn.y, wn.z);
    }
}

static void test_hits(const char *path, vec3 eye)
{
    struct scene_file sf = {0};
    struct err e;
    CHECK(scene_load(path, &sf, &e) == 0);
    if (!sf.scene)
        return;
    const struct scene *sc = sf.scene;
    CHECK(wide_usable(sc, 0) == 1);
    CHECK(wide_usable(sc, 1) == 0); /* light sampling off: today's lanes */
    struct wide_scene *ws = wide_scene_new(sc);
    CHECK(ws != NULL);
    if (!ws) {
        scene_file_free(&sf);
        return;
    }
    vec3 lo, hi;
    scene_box(sc, &lo, &hi);
    struct rng r;
    rng_seed(&r, 7, 7);
    struct tally ty = {0};
    ray q[WIDE_LANES];
    int n = 0;
    for (int i = 0; i < sc->n_prims; i++) {
        vec3 pl, ph;
        shape_bounds(&sc->prims[i], &pl, &ph);
        for (int k = 0; k < 27; k++) {
            const vec3 target = box_point(pl, ph, k);
            for (int rep = 0; rep < 4; rep++) {
                const vec3 inside =
                    v3(lo.x + rng_uniform(&r) * (hi.x - lo.x), lo.y + rng_uniform(&r) * (hi.y - lo.y),
                       lo.z + rng_uniform(&r) * (hi.z - lo.z));
                const vec3 rnd = v3(rng_uniform(&r) - 0.5, rng_uniform(&r) - 0.5, rng_uniform(&r) - 0.5);
                const ray set[4] = {
                    {inside, v3_sub(target, inside), 0},
                    {eye, v3_sub(target, eye), 0},
                    {v3_add(target, v3_scale(rnd, 10)), v3(k % 3 == 0, -(k % 3 == 1), k % 3 == 2), 0},
                    {inside, v3_unit(rnd), 0},
                };
                for (int s = 0; s < 4; s++) {
                    q[n++ % WIDE_LANES] = set[s];
                    if (n % WIDE_LANES)
                        continue;
                    compare(sc, ws, q, HIT_EPS, &ty);
                    /* on from the hits, in random directions (as paths go on) */
                    for (int j = 0; j < WIDE_LANES; j++) {
                        struct hit h;
                        const vec3 dir =
                            v3_unit(v3(rng_uniform(&r) - 0.5, rng_uniform(&r) - 0.5, rng_uniform(&r) - 0.5));
                        if (bvh_hit(sc, &q[j], HIT_EPS, DBL_MAX, &h))
                            q[j] = (ray){v3_fma(h.p, h.n, v3_dot(dir, h.n) > 0 ? 1e-3 : -1e-3), dir, 0};
                    }
                    compare(sc, ws, q, HIT_EPS, &ty);
                }
            }
        }
    }
    fprintf(stderr, "%s: %d rays, %d hits, %d edge ties, %d wrong\n", path, ty.rays, ty.hits, ty.ties,
            ty.bad);
    CHECK(ty.bad == 0);
    CHECK(ty.ties * 20 < ty.rays); /* under 5%: only rays aimed at edges and corners */
    CHECK(ty.hits > ty.rays / 2);
    wide_scene_free(ws);
    scene_file_free(&sf);
}

/* The mean luminance of a W x W render of sf (jitter at t=2.5: 1600 samples per pixel), its whole
   image and its lower half: the wide kernel's with light sampling, today's lanes' without. */
#define W 16
static int render_means(const struct scene_file *sf, int light_off, uint64_t seed, double out[2])
{
    struct err e;
    struct camera cam;
    if (camera_init(&cam, &sf->camera, 1.0, &e) < 0)
        return -1;
    struct sampler *pix = sampler_new(SAMPLER_JITTER, 2.5, 0, seed * 7 + 1, &e);
    struct sampler *light = sampler_new(SAMPLER_JITTER, 2.5, 0, seed * 7 + 2, &e);
    struct render_settings rs = {W, W, 50, seed, light_off};
    struct render_ctx *ctx = pix && light ? render_ctx_new(sf->scene, &cam, &rs, pix, light, &e) : NULL;
    int rc = -1;
    if (ctx) {
        struct render_stats st;
        render_stats_init(&st);
        out[0] = out[1] = 0;
        for (int y = 0; y < W; y++)
            for (int x = 0; x < W; x++) {
                float c[3];
                render_pixel(ctx, x, y, c, &st);
                const double lum = (c[0] + c[1] + c[2]) / 3;
                out[0] += lum / (W * W);
                out[1] += y >= W / 2 ? lum / (W * W / 2) : 0;
            }
        rc = 0;
    }
    render_ctx_free(ctx);
    sampler_free(pix);
    sampler_free(light);
    return rc;
}

/* The wide kernel's estimator (light mixture, dielectric, in float) is unbiased: its image means
   agree with those of today's lanes without light sampling (cosine only, double) within 4
   standard errors of the seeds' means (2-4% of them). A mixture pdf weighted 0.4 / 0.6 instead of
   half and half fails both. */
static void test_unbiased(const char *path)
{
    struct scene_file sf = {0};
    struct err e;
    CHECK(scene_load(path, &sf, &e) == 0);
    if (!sf.scene)
        return;
    enum { SEEDS = 4 };
    double sum[2][2] = {{0}}, sum2[2][2] = {{0}};
    for (int off = 0; off < 2; off++)
        for (int s = 0; s < SEEDS; s++) {
            double m[2] = {0, 0};
            CHECK(render_means(&sf, off, 1 + s, m) == 0);
            for (int k = 0; k < 2; k++)
                sum[off][k] += m[k], sum2[off][k] += m[k] * m[k];
        }
    for (int k = 0; k < 2; k++) {
        double mean[2], var_of_mean = 0;
        for (int off = 0; off < 2; off++) {
            mean[off] = sum[off][k] / SEEDS;
            var_of_mean += fmax(0, sum2[off][k] / SEEDS - mean[off] * mean[off]) / (SEEDS - 1);
        }
        const double bound = 4 * sqrt(var_of_mean);
        fprintf(stderr, "%s %s: wide %.5f lanes (no light sampling) %.5f |diff| %.5f bound %.5f\n", path,
                k ? "lower half" : "image", mean[0], mean[1], fabs(mean[0] - mean[1]), bound);
        CHECK(fabs(mean[0] - mean[1]) < bound);
    }
    scene_file_free(&sf);
}

/* A small sphere far from the eye: rays grazing it (aimed at its silhouette, from the eye) hit it
   at a point within the kernel's origin offset (16 float ulps of |p| + |o|: more than of 555) of
   its surface, or the bounce's new origin may lie inside and its ray hit the sphere again (the
   sphere's tops under the light came out darker). The quadratic's discriminant in the textbook
   form, b^2 - a c of terms |o - c|^2 ~ 1e6, put these points up to 5e-3 off. */
/* YAML text into a new temporary file, its name into path (at least 32 bytes): 0, or -1. */
static int write_temp(const char *text, char *path)
{
    snprintf(path, 32, "/tmp/test_wide_XXXXXX");
    const int fd = mkstemp(path);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f)
        return -1;
    fputs(text, f);
    fclose(f);
    return 0;
}

/* The scene of YAML text into *sf through a temporary file: scene_load's return. */
static int load_text(const char *text, struct scene_file *sf)
{
    char path[32];
    if (write_temp(text, path) < 0)
        return -1;
    struct err e;
    const int rc = scene_load(path, sf, &e);
    remove(path);
    return rc;
}

/* A floor of albedo ALBEDO, a rect light of emission EMIT, a small sphere; background BG. */
#define SMALL_SCENE(ALBEDO, EMIT, BG)                                                                        \
    "camera: { lookfrom: [278, 278, -800], lookat: [278, 278, 0], vup: [0, 1, 0], vfov: 40 }\n"              \
    "background: " BG "\n"                                                                                   \
    "materials: { white: { type: lambertian, albedo: " ALBEDO " },\n"                                        \
    "             lamp: { type: light, emit: " EMIT " } }\n"                                                 \
    "objects:\n"                                                                                             \
    "  - { type: rect, plane: xz, min: [0, 0], max: [555, 555], at: 0, material: white }\n"                  \
    "  - { type: rect, plane: xz, min: [213, 227], max: [343, 332], at: 554, flip: true, "                   \
    "material: lamp }\n"                                                                                     \
    "  - { type: sphere, center: [278, 400, 300], radius: 10, material: white }\n"

static void test_graze(void)
{
    struct scene_file sf = {0};
    CHECK(load_text(SMALL_SCENE("[0.7, 0.7, 0.7]", "[15, 15, 15]", "[0, 0, 0]"), &sf) == 0);
    if (!sf.scene)
        return;
    struct wide_scene *ws = wide_usable(sf.scene, 0) ? wide_scene_new(sf.scene) : NULL;
    CHECK(ws != NULL);
    const vec3 eye = v3(278, 278, -800), c = v3(278, 400, 300);
    const double r = 10, bound = 555 * 0x1p-20;
    double worst = 0;
    int hits = 0;
    for (int k = 0; ws && k < 64; k++) {
        double o[3 * WIDE_LANES], d[3 * WIDE_LANES], t[WIDE_LANES], n[3 * WIDE_LANES];
        int prim[WIDE_LANES];
        for (int i = 0; i < WIDE_LANES; i++) {
            /* around the silhouette, from 1 - 1e-1 to 1 - 1e-8 of the radius off the centre */
            const double a = 2 * PI * k / 64, off = r * (1 - pow(10, -1 - i));
            const vec3 dir = v3_sub(v3(c.x + off * cos(a), c.y + off * sin(a), c.z), eye);
            o[i] = eye.x, o[WIDE_LANES + i] = eye.y, o[2 * WIDE_LANES + i] = eye.z;
            d[i] = dir.x, d[WIDE_LANES + i] = dir.y, d[2 * WIDE_LANES + i] = dir.z;
        }
        wide_scene_hit(ws, o, d, HIT_EPS, t, prim, n);
        for (int i = 0; i < WIDE_LANES; i++) {
            if (prim[i] != 2)
                continue;
            hits++;
            const vec3 p = v3(o[i] + t[i] * d[i], o[WIDE_LANES + i] + t[i] * d[WIDE_LANES + i],
                              o[2 * WIDE_LANES + i] + t[i] * d[2 * WIDE_LANES + i]);
            worst = fmax(worst, fabs(v3_len(v3_sub(p, c)) - r));
        }
    }
    fprintf(stderr,
            "grazing a sphere of radius 10 from 1100 away: %d hits, worst %.3g off its surface "
            "(bound %.3g)\n",
            hits, worst, bound);
    CHECK(hits > 64 * 6);
    CHECK(worst < bound);
    wide_scene_free(ws);
    scene_file_free(&sf);
}

/* Radiance beyond float's range (emit, background and albedo are unbounded, >= 0): the lanes' float
   made it inf and the sidecar counted every sample that met it as dropped (75809 of 230400 in
   a 48x48 cornell-book3 with emit 1e39, black where the scalar path's image is white). No
   sample of such a scene is dropped (its pixels are floats: they may still be inf). */
static void test_radiance(const char *albedo, const char *emit, const char *bg)
{
    char text[2048];
    snprintf(text, sizeof text, SMALL_SCENE("%s", "%s", "%s"), bg, albedo, emit); /* in the text's order */
    struct scene_file sf = {0};
    struct err e;
    CHECK(load_text(text, &sf) == 0);
    if (!sf.scene)
        return;
    struct camera cam;
    CHECK(camera_init(&cam, &sf.camera, 1.0, &e) == 0);
    struct sampler *pix = sampler_new(SAMPLER_RANDOM, 20, 0, 1, &e);
    struct sampler *light = sampler_new(SAMPLER_RANDOM, 20, 0, 2, &e);
    struct render_settings rs = {8, 8, 50, 1, 0};
    struct render_ctx *ctx = pix && light ? render_ctx_new(sf.scene, &cam, &rs, pix, light, &e) : NULL;
    CHECK(ctx != NULL);
    struct render_stats st;
    render_stats_init(&st);
    for (int y = 0; ctx && y < 8; y++)
        for (int x = 0; x < 8; x++) {
            float c[3];
            render_pixel(ctx, x, y, c, &st);
        }
    fprintf(stderr, "albedo %s, emit %s, background %s: %llu of %llu samples dropped\n", albedo, emit, bg,
            (unsigned long long)st.nonfinite, (unsigned long long)st.samples);
    CHECK(st.nonfinite == 0);
    render_ctx_free(ctx);
    sampler_free(pix);
    sampler_free(light);
    scene_file_free(&sf);
}

/* cornell-book3 seen from 1e5 away (vfov 0.3: about the same view): the camera rays' float hit
   points rounded at 1e5's scale (ulp 0.008), far beyond the new origin's offset (16 ulps of the
   scene's 770): bounces began inside the box, whose face came out at half its brightness. */
static void test_far_eye(void)
{
    char text[4096], path[32];
    FILE *f = fopen("scenes/cornell-book3.yaml", "r");
    const size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f)
        fclose(f);
    text[n] = 0;
    char *eye = strstr(text, "lookfrom: [278, 278, -800]"), *fov = strstr(text, "vfov: 40");
    CHECK(eye && fov);
    if (!eye || !fov)
        return;
    memcpy(eye, "lookfrom: [278, 278, -1e5]", 26);
    memcpy(fov, "vfov: .3", 8);
    CHECK(write_temp(text, path) == 0);
    test_unbiased(path);
    remove(path);
}

/* A glass sphere of radius 0.05 on a floor 2e5 across, seen from close by: the new origins'
   offset was one for the whole scene, 16 float ulps of its reach (0.1 here, the sphere's
   diameter), so a refracted ray began beyond the sphere's far side and never left it (image means
   0.60 against 0.53; a block of it 0.28 against 0.77). Against the lanes without light sampling,
   as test_unbiased. */
static void test_big_floor(void)
{
    char path[32];
    const char *text =
        "camera: { lookfrom: [0, 0.12, -0.4], lookat: [0, 0.05, 0], vup: [0, 1, 0], vfov: 20 }\n"
        "materials: { white: { type: lambertian, albedo: [0.73, 0.73, 0.73] },\n"
        "             glass: { type: dielectric, ior: 1.5 }, lamp: { type: light, emit: [15, 15, 15] } }\n"
        "objects:\n"
        "  - { type: rect, plane: xz, min: [-1e5, -1e5], max: [1e5, 1e5], at: 0, material: white }\n"
        "  - { type: rect, plane: xz, min: [-1, -1], max: [1, 1], at: 4, flip: true, material: lamp }\n"
        "  - { type: sphere, center: [0, 0.05, 0], radius: 0.05, material: glass }\n";
    CHECK(write_temp(text, path) == 0);
    test_unbiased(path);
    remove(path);
}

/* cornell-book3 moved by 1e6 on every axis: in float its points rounded to 1/16 (the image 1.5
   times as noisy as the scalar path's, its light's pdf off near the light); the lanes work
   relative to the scene's centre, so its hits are as good as at home. */
static void test_moved(void)
{
    char path[32];
    const char *text =
        "camera: { lookfrom: [1000278, 1000278, 999200], lookat: [1000278, 1000278, 1000000], vup: [0, 1, "
        "0],\n"
        "          vfov: 40 }\n"
        "materials: { red: { type: lambertian, albedo: [0.65, 0.05, 0.05] },\n"
        "  white: { type: lambertian, albedo: [0.73, 0.73, 0.73] },\n"
        "  green: { type: lambertian, albedo: [0.12, 0.45, 0.15] },\n"
        "  glass: { type: dielectric, ior: 1.5 }, lamp: { type: light, emit: [15, 15, 15] } }\n"
        "objects:\n"
        "  - { type: rect, plane: yz, min: [1e6, 1e6], max: [1000555, 1000555], at: 1000555, material: green "
        "}\n"
        "  - { type: rect, plane: yz, min: [1e6, 1e6], max: [1000555, 1000555], at: 1e6, material: red }\n"
        "  - { type: rect, plane: xz, min: [1000213, 1000227], max: [1000343, 1000332], at: 1000554, flip: "
        "true,\n"
        "      material: lamp }\n"
        "  - { type: rect, plane: xz, min: [1e6, 1e6], max: [1000555, 1000555], at: 1000555, material: white "
        "}\n"
        "  - { type: rect, plane: xz, min: [1e6, 1e6], max: [1000555, 1000555], at: 1e6, material: white }\n"
        "  - { type: rect, plane: xy, min: [1e6, 1e6], max: [1000555, 1000555], at: 1000555, material: white "
        "}\n"
        "  - { type: box, min: [0, 0, 0], max: [165, 330, 165], material: white, rotate_y: 15,\n"
        "      translate: [1000265, 1e6, 1000295] }\n"
        "  - { type: sphere, center: [1000190, 1000090, 1000190], radius: 90, material: glass, sample: true "
        "}\n";
    CHECK(write_temp(text, path) == 0);
    test_hits(path, v3(1000278, 1000278, 999200));
    remove(path);
}

static void test_usable(const char *path, int want)
{
    struct scene_file sf = {0};
    struct err e;
    CHECK(scene_load(path, &sf, &e) == 0);
    if (sf.scene)
        CHECK(wide_usable(sf.scene, 0) == want);
    scene_file_free(&sf);
}

int main(void)
{
#if WIDE_KERNEL
    if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) {
#endif
        fprintf(stderr,
                "test_wide: no AVX2 and FMA here (or not built), the kernel is never used: skipped\n");
        return check_report("test_wide");
#if WIDE_KERNEL
    }
#endif
    test_hits("scenes/cornell-book3.yaml", v3(278, 278, -800));
    test_unbiased("scenes/cornell-book3.yaml");
    test_graze();
    test_far_eye();
    test_big_floor();
    test_moved();
    test_radiance("[0.7, 0.7, 0.7]", "[1e39, 1e39, 1e39]", "[0, 0, 0]");
    test_radiance("[0.7, 0.7, 0.7]", "[15, 15, 15]", "[1e39, 0, 0]");
    test_radiance("[1e30, 1, 1]", "[15, 15, 15]", "[0, 0, 0]");
    test_radiance("[0.7, 0.7, 0.7]", "[15, 15, 15]", "[0, 0, 0]");
    test_usable("scenes/checker.yaml", 0); /* a disk and a texture: today's lanes */
    test_usable("scenes/cornell.yaml", 0); /* a cylinder */
    test_usable("scenes/final.yaml", 0);   /* many nodes */
    return check_report("test_wide");
}
