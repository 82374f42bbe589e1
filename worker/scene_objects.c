/* scene_objects: the `objects:` list of a scene file, one primitive (or a few) per entry. */
#include <stdio.h>
#include <string.h>

#include "scene_loader.h"

/* Keys every object may have besides its geometry. */
#define COMMON_KEYS "type", "material", "rotate_y", "translate", "sample"

static const char *const sphere_keys[] = {COMMON_KEYS, "center", "radius", NULL};
static const char *const rect_keys[] = {COMMON_KEYS, "plane", "min", "max", "at", "flip", NULL};
static const char *const disk_keys[] = {COMMON_KEYS, "center", "toward", "radius", NULL};

static int need(struct loader *L, yaml_node_t *n, const char *key, const char *type, yaml_node_t **out)
{
    if (!(*out = ymap_get(&L->d, n, key)))
        return ydoc_fail(&L->d, n, L->e, "%s: missing in %s", key, type);
    return 0;
}

static int positive(struct loader *L, yaml_node_t *n, const char *key, const char *type, double *out)
{
    yaml_node_t *v;
    if (need(L, n, key, type, &v) < 0 || yget_double(&L->d, v, key, out, L->e) < 0)
        return -1;
    if (!(*out > 0))
        return ydoc_fail(&L->d, v, L->e, "%s: must be > 0, got %g", key, *out);
    return 0;
}

static int point(struct loader *L, yaml_node_t *n, const char *key, const char *type, vec3 *out)
{
    yaml_node_t *v;
    if (need(L, n, key, type, &v) < 0)
        return -1;
    return yget_vec3(&L->d, v, key, out, L->e);
}

static int load_sphere(struct loader *L, yaml_node_t *n, struct prim *p)
{
    p->type = PRIM_SPHERE;
    if (point(L, n, "center", "sphere", &p->g.sphere.center) < 0 ||
        positive(L, n, "radius", "sphere", &p->g.sphere.radius) < 0)
        return -1;
    return 0;
}

static int load_rect(struct loader *L, yaml_node_t *n, struct prim *p)
{
    yaml_node_t *v;
    const char *plane;
    p->type = PRIM_RECT;
    if (need(L, n, "plane", "rect", &v) < 0 || yget_string(&L->d, v, "plane", &plane, L->e) < 0)
        return -1;
    if (!strcmp(plane, "yz"))
        p->g.rect.axis = 0;
    else if (!strcmp(plane, "xz"))
        p->g.rect.axis = 1;
    else if (!strcmp(plane, "xy"))
        p->g.rect.axis = 2;
    else
        return ydoc_fail(&L->d, v, L->e, "plane: must be xy, xz or yz, got \"%.20s\"", plane);
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
    return 0;
}

static int load_disk(struct loader *L, yaml_node_t *n, struct prim *p)
{
    vec3 toward;
    p->type = PRIM_DISK;
    if (point(L, n, "center", "disk", &p->g.disk.center) < 0 ||
        point(L, n, "toward", "disk", &toward) < 0 ||
        positive(L, n, "radius", "disk", &p->g.disk.radius) < 0)
        return -1;
    vec3 dir = v3_sub(toward, p->g.disk.center);
    if (v3_len(dir) == 0)
        return ydoc_fail(&L->d, ymap_get(&L->d, n, "toward"), L->e, "toward: must differ from center");
    onb f = onb_from_w(v3_unit(dir));
    p->g.disk.normal = f.w;
    p->g.disk.e1 = f.u;
    p->g.disk.e2 = f.v;
    return 0;
}

/* material, rotate_y, translate and sample: the keys any object takes. */
static int load_common(struct loader *L, yaml_node_t *n, struct prim *p, int *sample)
{
    yaml_node_t *v;
    const char *s;
    if (need(L, n, "material", "object", &v) < 0 || yget_string(&L->d, v, "material", &s, L->e) < 0)
        return -1;
    if ((p->material = loader_find_name(&L->mat, s)) < 0)
        return ydoc_fail(&L->d, v, L->e, "material: no material named \"%.40s\" in materials", s);
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

static int load_object(struct loader *L, yaml_node_t *n)
{
    struct prim p = {0};
    yaml_node_t *tn;
    const char *type;
    if (!n || n->type != YAML_MAPPING_NODE)
        return ydoc_fail(&L->d, n, L->e, "objects: each object must be a mapping {type: ...}");
    if (need(L, n, "type", "object", &tn) < 0 || yget_string(&L->d, tn, "type", &type, L->e) < 0)
        return -1;
    int rc;
    if (!strcmp(type, "sphere"))
        rc = ymap_check(&L->d, n, sphere_keys, "sphere", L->e) < 0 ? -1 : load_sphere(L, n, &p);
    else if (!strcmp(type, "rect"))
        rc = ymap_check(&L->d, n, rect_keys, "rect", L->e) < 0 ? -1 : load_rect(L, n, &p);
    else if (!strcmp(type, "disk"))
        rc = ymap_check(&L->d, n, disk_keys, "disk", L->e) < 0 ? -1 : load_disk(L, n, &p);
    else
        return ydoc_fail(&L->d, tn, L->e, "type: unknown object type \"%.40s\" (expected sphere, rect or disk)", type);
    int sample;
    if (rc < 0 || load_common(L, n, &p, &sample) < 0)
        return -1;
    int is_light = L->sc->materials[p.material].type == MAT_LIGHT;
    if (is_light || sample) {
        if (p.type == PRIM_SPHERE)
            return ydoc_fail(&L->d, n, L->e, "sample: spheres cannot be importance-sampled yet");
        if (p.has_xform)
            return ydoc_fail(&L->d, n, L->e, "rotate_y: lights and sampled objects cannot be transformed; place them directly");
    }
    int idx = scene_add_prim(L->sc, &p);
    if (idx < 0 || ((is_light || sample) && scene_add_light(L->sc, idx) < 0))
        return ydoc_fail(&L->d, n, L->e, "out of memory");
    return 0;
}

int load_objects(struct loader *L, yaml_node_t *list, yaml_node_t *root)
{
    if (!list)
        return ydoc_fail(&L->d, root, L->e, "objects: missing in scene");
    int n = yseq_len(list);
    if (n < 0)
        return ydoc_fail(&L->d, list, L->e, "objects: must be a list of objects");
    for (int i = 0; i < n; i++)
        if (load_object(L, yseq_item(&L->d, list, i)) < 0)
            return -1;
    return 0;
}
