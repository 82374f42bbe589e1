/* scene_objects: the `objects:` list of a scene file, one primitive (or a few) per entry. */
#include <stdlib.h>
#include <string.h>

#include "scene_objects.h"
#include "geom/shape.h"
#include "yget.h"

/* Keys every object may have besides its geometry. */
#define COMMON_KEYS "type", "material", "rotate_y", "translate", "sample"

/* Most primitives one object entry makes (a pyramid's four triangles). */
#define OBJECT_MAX_PRIMS 4

static const char *const sphere_keys[] = {COMMON_KEYS, "center", "radius", NULL};
static const char *const moving_sphere_keys[] = {COMMON_KEYS, "center0", "center1", "radius", NULL};
static const char *const rect_keys[] = {COMMON_KEYS, "plane", "min", "max", "at", "flip", NULL};
static const char *const disk_keys[] = {COMMON_KEYS, "center", "toward", "radius", NULL};
static const char *const box_keys[] = {COMMON_KEYS, "min", "max", NULL};
static const char *const cylinder_keys[] = {COMMON_KEYS, "base", "top", "radius", NULL};
static const char *const triangle_keys[] = {COMMON_KEYS, "vertices", NULL};
static const char *const pyramid_keys[] = {COMMON_KEYS, "apex", "base", NULL};
static const char *const medium_keys[] = {"type",     "material", "rotate_y", "translate",
                                          "boundary", "density",  NULL};
static const char *const boundary_keys[] = {"type", "center", "radius", NULL};

static int need(struct scene_parse *L, yaml_node_t *n, const char *key, const char *type, yaml_node_t **out)
{
    if (!(*out = ymap_get(&L->d, n, key)))
        return ymap_missing(&L->d, n, key, L->e, "%s: missing in %s", key, type);
    return 0;
}

static int positive(struct scene_parse *L, yaml_node_t *n, const char *key, const char *type, double *out)
{
    yaml_node_t *v;
    if (need(L, n, key, type, &v) < 0 || yget_double(&L->d, v, key, out, L->e) < 0)
        return -1;
    if (!(*out > 0))
        return ydoc_fail(&L->d, v, L->e, "%s: must be > 0, got %g", key, *out);
    if (*out < SCENE_MIN_SIZE)
        return ydoc_fail(&L->d, v, L->e, "%s: must be at least %g, got %g (its square underflows)", key,
                         SCENE_MIN_SIZE, *out);
    return 0;
}

static int point(struct scene_parse *L, yaml_node_t *n, const char *key, const char *type, vec3 *out)
{
    yaml_node_t *v;
    if (need(L, n, key, type, &v) < 0)
        return -1;
    return yget_vec3(&L->d, v, key, out, L->e);
}

/* A list of exactly three points under key. */
static int three_points(struct scene_parse *L, yaml_node_t *n, const char *key, const char *type, vec3 out[3],
                        yaml_node_t **node)
{
    if (need(L, n, key, type, node) < 0)
        return -1;
    if (yseq_len(*node) != 3)
        return ydoc_fail(&L->d, *node, L->e, "%s: must be a list of three points [[x, y, z], ...]", key);
    for (int i = 0; i < 3; i++)
        if (yget_vec3(&L->d, yseq_item(&L->d, *node, i), key, &out[i], L->e) < 0)
            return -1;
    return 0;
}

/* Triangle a, b, c; -1 (no error set) when it has no area relative to its size. */
static int make_triangle(struct prim *p, vec3 a, vec3 b, vec3 c)
{
    p->type = PRIM_TRIANGLE;
    p->g.tri.v0 = a;
    p->g.tri.e1 = v3_sub(b, a);
    p->g.tri.e2 = v3_sub(c, a);
    vec3 n = v3_cross(p->g.tri.e1, p->g.tri.e2);
    double scale = fmax(v3_len2(p->g.tri.e1), v3_len2(p->g.tri.e2));
    if (!(v3_len(n) > 1e-9 * scale))
        return -1;
    p->g.tri.normal = v3_unit(n);
    return 0;
}

static int load_sphere(struct scene_parse *L, yaml_node_t *n, struct prim *p)
{
    p->type = PRIM_SPHERE;
    if (point(L, n, "center", "sphere", &p->g.sphere.center) < 0 ||
        positive(L, n, "radius", "sphere", &p->g.sphere.radius) < 0)
        return -1;
    return 1;
}

static int load_moving_sphere(struct scene_parse *L, yaml_node_t *n, struct prim *p)
{
    vec3 c1;
    p->type = PRIM_MOVING_SPHERE;
    if (point(L, n, "center0", "moving_sphere", &p->g.msphere.center0) < 0 ||
        point(L, n, "center1", "moving_sphere", &c1) < 0 ||
        positive(L, n, "radius", "moving_sphere", &p->g.msphere.radius) < 0)
        return -1;
    p->g.msphere.velocity = v3_sub(c1, p->g.msphere.center0); /* center0 at time 0, center1 at 1 */
    p->g.msphere.time_lo = L->cam->shutter0;
    p->g.msphere.time_hi = L->cam->shutter1;
    return 1;
}

static int load_rect(struct scene_parse *L, yaml_node_t *n, struct prim *p)
{
    yaml_node_t *v;
    const char *plane;
    p->type = PRIM_RECT;
    if (need(L, n, "plane", "rect", &v) < 0 || yget_string(&L->d, v, "plane", &plane, L->e) < 0)
        return -1;
    static const char *const planes[3] = {"yz", "xz", "xy"}; /* by normal axis */
    int axis = 0;
    while (axis < 3 && strcmp(plane, planes[axis]))
        axis++;
    if (axis == 3)
        return ydoc_fail(&L->d, v, L->e, "plane: must be xy, xz or yz, got \"%.20s\"", plane);
    p->g.rect.axis = axis;
    double lo[2], hi[2];
    yaml_node_t *mn, *mx, *at;
    if (need(L, n, "min", "rect", &mn) < 0 || yget_vec2(&L->d, mn, "min", lo, L->e) < 0 ||
        need(L, n, "max", "rect", &mx) < 0 || yget_vec2(&L->d, mx, "max", hi, L->e) < 0 ||
        need(L, n, "at", "rect", &at) < 0 || yget_double(&L->d, at, "at", &p->g.rect.k, L->e) < 0)
        return -1;
    if (!(hi[0] > lo[0] && hi[1] > lo[1]))
        return ydoc_fail(&L->d, mx, L->e, "max: must exceed min on both axes (a rect needs an area)");
    p->g.rect.a0 = lo[0], p->g.rect.a1 = hi[0];
    p->g.rect.b0 = lo[1], p->g.rect.b1 = hi[1];
    if ((v = ymap_get(&L->d, n, "flip")) && yget_bool(&L->d, v, "flip", &p->flip, L->e) < 0)
        return -1;
    return 1;
}

static int load_disk(struct scene_parse *L, yaml_node_t *n, struct prim *p)
{
    vec3 toward;
    p->type = PRIM_DISK;
    if (point(L, n, "center", "disk", &p->g.disk.center) < 0 || point(L, n, "toward", "disk", &toward) < 0 ||
        positive(L, n, "radius", "disk", &p->g.disk.radius) < 0)
        return -1;
    vec3 dir = v3_sub(toward, p->g.disk.center);
    if (v3_len(dir) == 0)
        return ydoc_fail(&L->d, ymap_get(&L->d, n, "toward"), L->e, "toward: must differ from center");
    onb f = onb_from_w(v3_unit(dir));
    p->g.disk.normal = f.w;
    p->g.disk.e1 = f.u;
    p->g.disk.e2 = f.v;
    return 1;
}

static int load_box(struct scene_parse *L, yaml_node_t *n, struct prim *p)
{
    yaml_node_t *mx;
    p->type = PRIM_BOX;
    if (point(L, n, "min", "box", &p->g.box.lo) < 0 || point(L, n, "max", "box", &p->g.box.hi) < 0)
        return -1;
    mx = ymap_get(&L->d, n, "max");
    vec3 lo = p->g.box.lo, hi = p->g.box.hi;
    if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
        return ydoc_fail(&L->d, mx, L->e, "max: must exceed min on all three axes (a box needs a volume)");
    return 1;
}

static int load_cylinder(struct scene_parse *L, yaml_node_t *n, struct prim *p)
{
    vec3 top;
    p->type = PRIM_CYLINDER;
    if (point(L, n, "base", "cylinder", &p->g.cyl.base) < 0 || point(L, n, "top", "cylinder", &top) < 0 ||
        positive(L, n, "radius", "cylinder", &p->g.cyl.radius) < 0)
        return -1;
    vec3 axis = v3_sub(top, p->g.cyl.base);
    p->g.cyl.height = v3_len(axis);
    if (!(p->g.cyl.height > 1e-9 * p->g.cyl.radius))
        return ydoc_fail(&L->d, ymap_get(&L->d, n, "top"), L->e,
                         "top: must differ from base (a zero-length cylinder)");
    p->g.cyl.axis = v3_scale(axis, 1.0 / p->g.cyl.height);
    return 1;
}

static int load_triangle(struct scene_parse *L, yaml_node_t *n, struct prim *p)
{
    vec3 v[3];
    yaml_node_t *vn;
    if (three_points(L, n, "vertices", "triangle", v, &vn) < 0)
        return -1;
    if (make_triangle(p, v[0], v[1], v[2]) < 0)
        return ydoc_fail(&L->d, vn, L->e, "vertices: degenerate triangle (the three points are on one line)");
    return 1;
}

/* A pyramid: the base triangle and three sides to the apex. */
static int load_pyramid(struct scene_parse *L, yaml_node_t *n, struct prim *p)
{
    vec3 apex, b[3];
    yaml_node_t *bn;
    if (point(L, n, "apex", "pyramid", &apex) < 0 || three_points(L, n, "base", "pyramid", b, &bn) < 0)
        return -1;
    if (make_triangle(&p[0], b[0], b[1], b[2]) < 0)
        return ydoc_fail(&L->d, bn, L->e, "base: degenerate triangle (the three points are on one line)");
    double height = fabs(v3_dot(v3_sub(apex, b[0]), p[0].g.tri.normal));
    double size = sqrt(fmax(v3_len2(p[0].g.tri.e1), v3_len2(p[0].g.tri.e2)));
    if (!(height > 1e-9 * size))
        return ydoc_fail(&L->d, ymap_get(&L->d, n, "apex"), L->e,
                         "apex: lies in the base's plane (a flat pyramid)");
    for (int i = 0; i < 3; i++)
        make_triangle(&p[1 + i], apex, b[i], b[(i + 1) % 3]);
    return 4;
}

/* A constant medium filling a sphere boundary. */
static int load_medium(struct scene_parse *L, yaml_node_t *n, struct prim *p)
{
    yaml_node_t *bn, *tn, *v;
    const char *type;
    double density;
    p->type = PRIM_MEDIUM;
    if (need(L, n, "boundary", "medium", &bn) < 0)
        return -1;
    if (bn->type != YAML_MAPPING_NODE)
        return ydoc_fail(&L->d, bn, L->e,
                         "boundary: must be a mapping {type: sphere, center: ..., radius: ...}");
    if (need(L, bn, "type", "boundary", &tn) < 0 || yget_string(&L->d, tn, "type", &type, L->e) < 0)
        return -1;
    if (strcmp(type, "sphere"))
        return ydoc_fail(&L->d, tn, L->e, "type: a medium's boundary must be a sphere, got \"%.40s\"", type);
    if (ymap_check(&L->d, bn, boundary_keys, "boundary", L->e) < 0 ||
        point(L, bn, "center", "boundary", &p->g.medium.center) < 0 ||
        positive(L, bn, "radius", "boundary", &p->g.medium.radius) < 0 ||
        positive(L, n, "density", "medium", &density) < 0)
        return -1;
    if (!(density < 1e12))
        return ydoc_fail(&L->d, (v = ymap_get(&L->d, n, "density")), L->e, "density: must be < 1e12, got %g",
                         density);
    p->g.medium.neg_inv_density = -1.0 / density;
    return 1;
}

/* material, rotate_y, translate and sample: the keys any object takes. */
static int load_common(struct scene_parse *L, yaml_node_t *n, struct prim *p, int *sample)
{
    yaml_node_t *v;
    const char *s;
    if (need(L, n, "material", "object", &v) < 0 || yget_string(&L->d, v, "material", &s, L->e) < 0)
        return -1;
    if ((p->material = scene_parse_find_name(&L->mat, s)) < 0)
        return scene_parse_no_name(L, v, "material", s, &L->mat, "materials");
    double deg = 0;
    if ((v = ymap_get(&L->d, n, "rotate_y")) && yget_double(&L->d, v, "rotate_y", &deg, L->e) < 0)
        return -1;
    vec3 t = v3(0, 0, 0);
    if ((v = ymap_get(&L->d, n, "translate")) && yget_vec3(&L->d, v, "translate", &t, L->e) < 0)
        return -1;
    if (deg != 0 || ymap_get(&L->d, n, "translate")) {
        p->has_xform = 1;
        p->cos_y = cos(deg * PI / 180);
        p->sin_y = sin(deg * PI / 180);
        p->offset = t;
    }
    *sample = 0;
    if ((v = ymap_get(&L->d, n, "sample")) && yget_bool(&L->d, v, "sample", sample, L->e) < 0)
        return -1;
    return 0;
}

/* Every object type: its keys and the loader that fills 1..OBJECT_MAX_PRIMS prims (returning
   how many). Samplable types can be lights or `sample: true`. */
static const struct object_type {
    const char *name;
    const char *const *keys;
    int (*load)(struct scene_parse *, yaml_node_t *, struct prim *);
    int samplable;
} object_types[] = {
    {"sphere", sphere_keys, load_sphere, 1},
    {"moving_sphere", moving_sphere_keys, load_moving_sphere, 0},
    {"rect", rect_keys, load_rect, 1},
    {"disk", disk_keys, load_disk, 1},
    {"box", box_keys, load_box, 0},
    {"cylinder", cylinder_keys, load_cylinder, 0},
    {"triangle", triangle_keys, load_triangle, 0},
    {"pyramid", pyramid_keys, load_pyramid, 0},
    {"medium", medium_keys, load_medium, 0},
};
#define N_OBJECT_TYPES (int)(sizeof object_types / sizeof object_types[0])

/* Which materials an object may carry: media take isotropic only and only media do; image
   textures need surface coordinates, which spheres, rects and disks have; lights and sampled
   objects must be samplable and untransformed. */
static int check_placement(struct scene_parse *L, yaml_node_t *n, const struct object_type *ot,
                           const struct prim *p, int sample)
{
    const struct material *m = &L->sc->materials[p->material];
    yaml_node_t *mn = ymap_get(&L->d, n, "material");
    int medium = p->type == PRIM_MEDIUM;
    if (medium != (m->type == MAT_ISOTROPIC))
        return ydoc_fail(&L->d, mn, L->e,
                         medium ? "material: a medium needs an isotropic material"
                                : "material: isotropic materials fill media only");
    const int needs_uv = scene_prim_needs_uv(L->sc, p);
    if (needs_uv && !(p->type == PRIM_SPHERE || p->type == PRIM_RECT || p->type == PRIM_DISK))
        return ydoc_fail(&L->d, mn, L->e,
                         "material: an image texture needs a sphere, rect or disk (a %s has no uv)",
                         ot->name);
    if (m->type != MAT_LIGHT && !sample)
        return 0;
    if (!ot->samplable)
        return ydoc_fail(
            &L->d, sample ? ymap_get(&L->d, n, "sample") : mn, L->e,
            "%s: a %s cannot be importance-sampled (lights and sample: true take sphere, rect or disk)",
            sample ? "sample" : "material", ot->name);
    /* a light is sampled in world space: its transform must fold into its geometry */
    if (p->has_xform && !shape_bakes(p, needs_uv)) {
        yaml_node_t *xn = ymap_get(&L->d, n, "rotate_y");
        if (p->type == PRIM_RECT && !needs_uv)
            return ydoc_fail(&L->d, xn, L->e,
                             "rotate_y: a light or sampled rect turns only by multiples of 90 degrees "
                             "(it stays axis-aligned)");
        return ydoc_fail(&L->d, xn ? xn : ymap_get(&L->d, n, "translate"), L->e,
                         "%s: a sampled %s with an image texture cannot be transformed; place it directly",
                         xn ? "rotate_y" : "translate", ot->name);
    }
    return 0;
}

/* The place of the object just added to sc->lights (for scene_parse_facing_away). 0 or -1. */
static int note_light(struct scene_parse *L, const yaml_node_t *n)
{
    int k = L->sc->n_lights - 1;
    if (k >= L->light_pos_cap) {
        int cap = L->light_pos_cap ? 2 * L->light_pos_cap : 16;
        int(*grown)[2] = realloc(L->light_pos, (size_t)cap * sizeof *grown);
        if (!grown)
            return -1;
        L->light_pos = grown;
        L->light_pos_cap = cap;
    }
    L->light_pos[k][0] = (int)n->start_mark.line + 1;
    L->light_pos[k][1] = (int)n->start_mark.column + 1;
    return 0;
}

static int load_object(struct scene_parse *L, yaml_node_t *n)
{
    struct prim p[OBJECT_MAX_PRIMS] = {{0}};
    yaml_node_t *tn;
    const char *type;
    if (!n || n->type != YAML_MAPPING_NODE)
        return ydoc_fail(&L->d, n, L->e, "objects: each object must be a mapping {type: ...}");
    if (need(L, n, "type", "object", &tn) < 0 || yget_string(&L->d, tn, "type", &type, L->e) < 0)
        return -1;
    const struct object_type *ot = NULL;
    for (int i = 0; i < N_OBJECT_TYPES; i++)
        if (!strcmp(type, object_types[i].name))
            ot = &object_types[i];
    if (!ot) {
        const char *names[N_OBJECT_TYPES + 1] = {NULL};
        for (int i = 0; i < N_OBJECT_TYPES; i++)
            names[i] = object_types[i].name;
        return scene_parse_unknown(
            L, tn, "type: unknown object type", type, names,
            "sphere, moving_sphere, rect, disk, box, cylinder, triangle, pyramid or medium");
    }
    int count, sample;
    if (ymap_check(&L->d, n, ot->keys, ot->name, L->e) < 0 || (count = ot->load(L, n, p)) < 0 ||
        load_common(L, n, &p[0], &sample) < 0 || check_placement(L, n, ot, &p[0], sample) < 0)
        return -1;
    int is_light = L->sc->materials[p[0].material].type == MAT_LIGHT;
    for (int i = 0; i < count; i++) {
        if (i > 0) { /* the parts of one object share its material and transform */
            p[i].material = p[0].material;
            p[i].has_xform = p[0].has_xform;
            p[i].cos_y = p[0].cos_y, p[i].sin_y = p[0].sin_y, p[i].offset = p[0].offset;
        }
        int idx = scene_add_prim(L->sc, &p[i]);
        if (idx < 0 || ((is_light || sample) && (scene_add_light(L->sc, idx) < 0 || note_light(L, n) < 0)))
            return ydoc_fail(&L->d, n, L->e, "out of memory");
    }
    return 0;
}

int scene_objects_load(struct scene_parse *L, yaml_node_t *list, yaml_node_t *root)
{
    if (!list)
        return ymap_missing(&L->d, root, "objects", L->e, "objects: missing in scene");
    int n = yseq_len(list);
    if (n < 0)
        return ydoc_fail(&L->d, list, L->e, "objects: must be a list of objects");
    for (int i = 0; i < n; i++)
        if (load_object(L, yseq_item(&L->d, list, i)) < 0)
            return -1;
    return 0;
}
