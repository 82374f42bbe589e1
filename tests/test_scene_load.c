/* Tests for the scene loader on the shipped scenes: every object becomes the primitives, lights
   and textures it should, and transforms and textures resolve as the scene file says. */
#include <float.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geom/bvh.h"
#include "check.h"
#include "image/imgio.h"
#include "scenefile/scene_load.h"

static int count_type(const struct scene *sc, int type)
{
    int n = 0;
    for (int i = 0; i < sc->n_prims; i++)
        n += sc->prims[i].type == type;
    return n;
}

static int load(const char *path, struct scene_file *sf)
{
    struct err e;
    if (scene_load(path, sf, &e) == 0)
        return 0;
    fprintf(stderr, "%s:%d:%d: %s\n", e.file, e.line, e.col, e.msg);
    return -1;
}

static void test_cornell(void)
{
    struct scene_file sf;
    CHECK(load("scenes/cornell.yaml", &sf) == 0);
    if (!sf.scene)
        return;
    const struct scene *sc = sf.scene;
    /* 5 walls, 3 disks, a box, a cylinder, a pyramid's 4 triangles, a sphere. */
    CHECK(sc->n_prims == 15);
    CHECK(count_type(sc, PRIM_RECT) == 5 && count_type(sc, PRIM_DISK) == 3);
    CHECK(count_type(sc, PRIM_BOX) == 1 && count_type(sc, PRIM_CYLINDER) == 1);
    CHECK(count_type(sc, PRIM_TRIANGLE) == 4 && count_type(sc, PRIM_SPHERE) == 1);
    CHECK(sc->n_lights == 3);
    for (int i = 0; i < sc->n_lights; i++)
        CHECK(sc->prims[sc->lights[i]].type == PRIM_DISK);
    CHECK(sc->n_images == 1 && sc->images[0].w == 256 && sc->images[0].h == 128);
    /* The pyramid's triangles share the object's transform, folded into their world-space
       vertices at load: its apex ends up at rotate_y(70) (0, 140, 0) + (150, 0, 350) =
       (150, 140, 350), a base vertex (140, 0, 0) at (150 + 140 cos 70, 0, 350 - 140 sin 70).
       The box keeps its transform. */
    int found_apex = 0, found_base = 0;
    const double c70 = cos(70 * PI / 180), s70 = sin(70 * PI / 180);
    for (int i = 0; i < sc->n_prims; i++) {
        const struct prim *p = &sc->prims[i];
        if (p->type == PRIM_BOX)
            CHECK(p->has_xform && fabs(p->sin_y - sin(10 * PI / 180)) < 1e-12);
        if (p->type != PRIM_TRIANGLE && p->type != PRIM_CYLINDER)
            continue;
        CHECK(!p->has_xform);
        if (p->type != PRIM_TRIANGLE)
            continue;
        CHECK_NEAR(v3_len(p->g.tri.normal), 1, 1e-12);
        found_apex += v3_len(v3_sub(p->g.tri.v0, v3(150, 140, 350))) < 1e-9;
        for (int k = 0; k < 3; k++) {
            vec3 v = k == 0 ? p->g.tri.v0 : v3_add(p->g.tri.v0, k == 1 ? p->g.tri.e1 : p->g.tri.e2);
            found_base += v3_len(v3_sub(v, v3(150 + 140 * c70, 0, 350 - 140 * s70))) < 1e-9;
        }
    }
    CHECK(found_apex == 3);
    CHECK(found_base == 3); /* the base triangle and the two sides that share the vertex */
    ray down = {v3(150, 500, 350), v3(0, -1, 0), 0};
    struct hit h;
    CHECK(bvh_hit(sc, &down, HIT_EPS, DBL_MAX, &h));
    CHECK(sc->prims[h.prim].type == PRIM_TRIANGLE);
    CHECK_NEAR(h.p.y, 140, 1e-6);
    /* The cylinder: base (0,0,0) -> (160, 230, 80) after the transform; its axis is rotated. */
    ray at_base = {v3(160, 230, 80), v3(0, 0, 1), 0}; /* starts inside, leaves through the side */
    CHECK(bvh_hit(sc, &at_base, HIT_EPS, DBL_MAX, &h) && sc->prims[h.prim].type == PRIM_CYLINDER);
    CHECK(!h.front);
    scene_file_free(&sf);
}

static void test_book3_and_final(void)
{
    struct scene_file sf;
    CHECK(load("scenes/cornell-book3.yaml", &sf) == 0);
    if (sf.scene) {
        const struct scene *sc = sf.scene;
        CHECK(sc->n_prims == 8 && sc->n_lights == 2);
        const struct prim *lamp = &sc->prims[sc->lights[0]];
        const struct prim *glass = &sc->prims[sc->lights[1]];
        CHECK(lamp->type == PRIM_RECT && lamp->flip && lamp->g.rect.k == 554);
        CHECK(glass->type == PRIM_SPHERE && sc->materials[glass->material].type == MAT_DIELECTRIC);
        /* next-event estimation's set: the lamp alone, not the sample: true glass */
        CHECK(sc->n_emitters == 1 && sc->emitters[0] == sc->lights[0] && sc->emitter_lights[0] == 0);
        scene_file_free(&sf);
    }
    CHECK(load("scenes/final.yaml", &sf) == 0);
    if (sf.scene) {
        const struct scene *sc = sf.scene;
        CHECK(count_type(sc, PRIM_BOX) == 400);
        CHECK(count_type(sc, PRIM_SPHERE) ==
              1005); /* the cluster, glass, metal, blue glass, planet, marble */
        CHECK(count_type(sc, PRIM_MEDIUM) == 2 && count_type(sc, PRIM_MOVING_SPHERE) == 1);
        CHECK(sc->n_lights == 1 && sc->perlin != NULL && sc->n_images == 1);
        CHECK(sf.camera.shutter0 == 0 && sf.camera.shutter1 == 1);
        CHECK(sc->n_nodes > 100 && sc->n_nodes < 2 * sc->n_prims);
        scene_file_free(&sf);
    }
    CHECK(load("scenes/checker.yaml", &sf) == 0);
    if (sf.scene) {
        CHECK(sf.scene->n_prims == 3 && sf.scene->n_lights == 1);
        scene_file_free(&sf);
    }
}

/* Write dir/name: a 512x512 PNG (768 KiB decoded). */
static void write_png(const char *dir, const char *name)
{
    char path[512];
    struct rgb8 img;
    struct err e;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    CHECK(image_alloc(&img, 512, 512, &e) == 0);
    for (size_t i = 0; img.px && i < (size_t)512 * 512 * 3; i++)
        img.px[i] = (uint8_t)(i * 7);
    CHECK(imgio_write(path, &img, IMG_PNG, &e) == 0);
    image_free(&img);
}

/* Thirteen image textures naming three files: each file decoded once (a.png also by another path), its pixels
   shared by the textures that name it (256 textures of one 4096x4096 file took 12 GiB); and the scene's
   decoded textures together within src's budget, refused at the `file` key that would pass it. */
static void test_shared_images(void)
{
    char dir[256], path[300];
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/test_scene_load.XXXXXX", tmp && *tmp ? tmp : "/tmp");
    CHECK(mkdtemp(dir) != NULL);
    write_png(dir, "a.png");
    write_png(dir, "b.png");
    write_png(dir, "c.png");
    snprintf(path, sizeof path, "%s/s.yaml", dir);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f)
        return;
    fprintf(f, "camera: { lookfrom: [0, 0, 5], lookat: [0, 0, 0], vfov: 40 }\ntextures:\n");
    for (int i = 0; i < 10; i++)
        fprintf(f, "  t%d: { type: image, file: a.png }\n", i);
    fprintf(f, "  u: { type: image, file: b.png }\n  v: { type: image, file: c.png }\n");
    fprintf(f, "  w: { type: image, file: ./a.png }\n"); /* another path to a.png */
    fprintf(f, "materials:\n  m: { type: lambertian, texture: t3 }\n  l: { type: light, emit: [4, 4, 4] }\n");
    fprintf(f, "objects:\n  - { type: sphere, center: [0, 0, 0], radius: 1, material: m }\n");
    fprintf(f, "  - { type: sphere, center: [0, 5, 0], radius: 1, material: l }\n");
    fclose(f);
    struct scene_file sf;
    CHECK(load(path, &sf) == 0);
    if (sf.scene) {
        const struct scene *sc = sf.scene;
        CHECK(sc->n_textures == 13 && sc->n_images == 3);
        int same = 1;
        for (int i = 1; i < 13; i += i == 9 ? 3 : 1) /* t1..t9 and w */
            same &= sc->textures[i].image == sc->textures[0].image;
        CHECK(same && sc->textures[10].image != sc->textures[0].image &&
              sc->textures[11].image != sc->textures[10].image);
        scene_file_free(&sf);
    }
    struct scene_src src;
    struct err e;
    uint64_t h = 0;
    CHECK(scene_src_read(path, &src, &h, &e) == 0);
    CHECK(src.texture_budget == (size_t)1 << 30); /* 1 GiB, as docs/scene-format.md says */
    src.texture_budget = (size_t)2 << 20;         /* two of the files, not three */
    CHECK(scene_load_src(&src, &sf, &e) == -1 && sf.scene == NULL);
    CHECK(e.line == 14 && e.col == 27 && strstr(e.msg, "file: texture ") &&
          strstr(e.msg, "c.png (512x512)") && strstr(e.msg, "2.25 MiB decoded, over the limit of 2 MiB"));
    src.texture_budget = (size_t)3 * 512 * 512 * 3; /* exactly all three */
    CHECK(scene_load_src(&src, &sf, &e) == 0);
    scene_file_free(&sf);
    scene_src_free(&src);
    const char *names[] = {"a.png", "b.png", "c.png", "s.yaml"};
    for (int i = 0; i < 4; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        unlink(path);
    }
    rmdir(dir);
}

/* A scene whose material m is `material` (a flow mapping's inside), loaded from a file under
   TMPDIR: 0 with *type m's type, or -1 with e filled. */
static int load_material(const char *material, int *type, struct err *e)
{
    char path[300];
    const char *tmp = getenv("TMPDIR");
    snprintf(path, sizeof path, "%s/test_scene_load_mat.XXXXXX", tmp && *tmp ? tmp : "/tmp");
    int fd = mkstemp(path);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f)
        return -1;
    fprintf(f, "camera: { lookfrom: [0, 0, 5], lookat: [0, 0, 0], vfov: 40 }\n");
    fprintf(f, "materials:\n  m: { %s }\n", material);
    fprintf(f, "objects:\n  - { type: sphere, center: [0, 0, 0], radius: 1, material: m }\n");
    fclose(f);
    struct scene_file sf;
    int rc = scene_load(path, &sf, e);
    *type = rc == 0 ? sf.scene->materials[0].type : -1;
    if (rc == 0)
        scene_file_free(&sf);
    unlink(path);
    return rc;
}

/* Each material type by its name, with the keys it takes; another type's key, an unknown type
   (and a near one) refused naming what is allowed. */
static void test_material_types(void)
{
    const char *ok[] = {"type: lambertian, albedo: [1, 0, 0]", "type: metal, albedo: [1, 1, 1], fuzz: 0.1",
                        "type: dielectric, ior: 1.3", "type: light, emit: [1, 1, 1]"};
    const int want[] = {MAT_LAMBERTIAN, MAT_METAL, MAT_DIELECTRIC, MAT_LIGHT};
    struct err e;
    int type;
    for (int i = 0; i < 4; i++)
        CHECK(load_material(ok[i], &type, &e) == 0 && type == want[i]);
    /* isotropic: read as such, refused on a sphere (a medium's material only) */
    CHECK(load_material("type: isotropic, albedo: [1, 1, 1]", &type, &e) < 0 &&
          strstr(e.msg, "isotropic materials fill media only"));
    CHECK(load_material("type: metal, albedo: [1, 1, 1], emit: [1, 1, 1]", &type, &e) < 0 &&
          !strcmp(e.msg, "emit: not a key of a metal material (it takes: albedo fuzz)"));
    CHECK(load_material("type: dielectric, texture: t", &type, &e) < 0 &&
          !strcmp(e.msg, "texture: not a key of a dielectric material (it takes: ior)"));
    CHECK(load_material("type: metl", &type, &e) < 0 &&
          !strcmp(e.msg, "type: unknown material type \"metl\" (did you mean \"metal\"?)"));
    CHECK(load_material("type: wood", &type, &e) < 0 &&
          !strcmp(e.msg,
                  "type: unknown material type \"wood\" (expected lambertian, metal, dielectric, light "
                  "or isotropic)"));
}

int main(void)
{
    test_material_types();
    test_cornell();
    test_book3_and_final();
    test_shared_images();
    return check_report("test_scene_load");
}
