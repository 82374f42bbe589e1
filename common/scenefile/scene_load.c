/* scene_load: validating a scene file and building the renderer's scene from it. */
#include "scene_load.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/fileio.h"
#include "image/imgio.h"
#include "scene_parse.h"
#include "scene_objects.h"
#include "yget.h"

enum { LO_OPEN = 1, HI_OPEN = 2 }; /* number_in: an end left out of the range */

/* The number at key of mapping n into *out when given (else *out kept), within [lo, hi] (an end
   left out by open), else "key: must be <rule>, got v". 0, or -1 with L->e filled. */
static int number_in(struct scene_parse *L, yaml_node_t *n, const char *key, double lo, double hi, int open,
                     const char *rule, double *out)
{
    yaml_node_t *v = ymap_get(&L->d, n, key);
    if (!v)
        return 0;
    if (yget_double(&L->d, v, key, out, L->e) < 0)
        return -1;
    const int below = open & LO_OPEN ? !(*out > lo) : *out < lo,
              above = open & HI_OPEN ? !(*out < hi) : *out > hi;
    if (below || above)
        return ydoc_fail(&L->d, v, L->e, "%s: must be %s, got %g", key, rule, *out);
    return 0;
}

static const char *const camera_keys[] = {"lookfrom",   "lookat",  "vup",    "vfov", "aperture",
                                          "focus_dist", "shutter", "aspect", NULL};

static int load_camera(struct scene_parse *L, yaml_node_t *n, struct scene_file *out)
{
    struct camera_desc *c = &out->camera;
    *c = (struct camera_desc){.vup = v3(0, 1, 0), .vfov_deg = 40, .focus_dist = 10};
    out->aspect = 1;
    if (ymap_check(&L->d, n, camera_keys, "camera", L->e) < 0)
        return -1;
    yaml_node_t *v;
    const char *need[] = {"lookfrom", "lookat", "vfov"};
    for (int i = 0; i < 3; i++)
        if (!ymap_get(&L->d, n, need[i]))
            return ymap_missing(&L->d, n, need[i], L->e, "%s: missing in camera", need[i]);
    if (yget_vec3(&L->d, ymap_get(&L->d, n, "lookfrom"), "lookfrom", &c->lookfrom, L->e) < 0 ||
        yget_vec3(&L->d, ymap_get(&L->d, n, "lookat"), "lookat", &c->lookat, L->e) < 0)
        return -1;
    if ((v = ymap_get(&L->d, n, "vup")) && yget_vec3(&L->d, v, "vup", &c->vup, L->e) < 0)
        return -1;
    if (number_in(L, n, "vfov", 0, 180, LO_OPEN | HI_OPEN, "in (0, 180) degrees", &c->vfov_deg) < 0 ||
        number_in(L, n, "aperture", 0, INFINITY, 0, ">= 0", &c->aperture) < 0 ||
        number_in(L, n, "focus_dist", 0, INFINITY, LO_OPEN, "> 0", &c->focus_dist) < 0)
        return -1;
    double sh[2] = {0, 1};
    if ((v = ymap_get(&L->d, n, "shutter"))) {
        if (yget_vec2(&L->d, v, "shutter", sh, L->e) < 0)
            return -1;
        if (sh[1] < sh[0])
            return ydoc_fail(&L->d, v, L->e, "shutter: must be [open, close] with open <= close");
    }
    c->shutter0 = sh[0];
    c->shutter1 = sh[1];
    if (number_in(L, n, "aspect", 0.01, 100, 0, "in [0.01, 100]", &out->aspect) < 0)
        return -1;
    struct camera probe;
    if (camera_init(&probe, c, out->aspect, L->e) < 0)
        return ydoc_fail(&L->d, n, L->e, "camera: %s", L->e->msg);
    return 0;
}

static const char *const texture_types[] = {"checker", "noise", "image", NULL};
/* The material types in enum mat_type's order, and the keys each takes besides type. */
static const char *const material_types[] = {"lambertian", "metal", "dielectric", "light", "isotropic", NULL};
static const char *const material_takes[] = {"albedo texture", "albedo fuzz", "ior", "emit",
                                             "albedo texture"};
_Static_assert(sizeof material_takes / sizeof *material_takes == MAT_ISOTROPIC + 1,
               "a row per material type");

static const char *const checker_keys[] = {"type", "odd", "even", "scale", NULL};
static const char *const noise_keys[] = {"type", "scale", NULL};
static const char *const image_keys[] = {"type", "file", NULL};

static int load_checker(struct scene_parse *L, yaml_node_t *n, struct texture *t)
{
    if (ymap_check(&L->d, n, checker_keys, "checker texture", L->e) < 0)
        return -1;
    t->type = TEX_CHECKER;
    t->scale = 10;
    const char *need[] = {"odd", "even"};
    for (int i = 0; i < 2; i++)
        if (!ymap_get(&L->d, n, need[i]))
            return ymap_missing(&L->d, n, need[i], L->e, "%s: missing in checker texture", need[i]);
    if (scene_parse_color(L, ymap_get(&L->d, n, "odd"), "odd", &t->odd) < 0 ||
        scene_parse_color(L, ymap_get(&L->d, n, "even"), "even", &t->even) < 0)
        return -1;
    return number_in(L, n, "scale", 0, INFINITY, LO_OPEN, "> 0", &t->scale);
}

static int load_noise(struct scene_parse *L, yaml_node_t *n, struct texture *t)
{
    if (ymap_check(&L->d, n, noise_keys, "noise texture", L->e) < 0)
        return -1;
    t->type = TEX_NOISE;
    t->scale = 1;
    if (number_in(L, n, "scale", 0, 1e6, LO_OPEN, "in (0, 1e6]", &t->scale) < 0)
        return -1;
    if (scene_use_perlin(L->sc) < 0)
        return ydoc_fail(&L->d, n, L->e, "out of memory");
    return 0;
}

/* The decoded image of texture file f (an entry of L->src) into *image: decoded on its first use
   (its size checked first, against the image and the scene's limits, before the memory is
   spent), then shared by every texture that names it. Errors at v, the texture's `file` key. */
static int image_of_file(struct scene_parse *L, yaml_node_t *v, const struct scene_src_file *f,
                         const char *path, int *image)
{
    int *seen = &L->file_image[f - L->src->files];
    if (*seen >= 0) {
        *image = *seen;
        return 0;
    }
    struct rgb8 img;
    struct err ie;
    int w, h;
    if (!f->bytes || imgio_size(f->bytes, f->len, path, &w, &h, &ie) < 0)
        return ydoc_fail(&L->d, v, L->e, "file: cannot read texture %s: %s", path,
                         f->bytes ? ie.msg : f->read_err.msg);
    if ((long)w * h > TEXTURE_MAX_PIXELS)
        return ydoc_fail(&L->d, v, L->e, "file: texture %s is %dx%d, over the limit of %ld pixels", path, w,
                         h, (long)TEXTURE_MAX_PIXELS);
    size_t bytes = (size_t)w * (size_t)h * 3;
    if (L->texture_bytes + bytes > L->src->texture_budget)
        return ydoc_fail(&L->d, v, L->e,
                         "file: texture %s (%dx%d) takes the scene's image textures to %.4g MiB decoded, "
                         "over the limit of %.4g MiB",
                         path, w, h, (double)(L->texture_bytes + bytes) / (1 << 20),
                         (double)L->src->texture_budget / (1 << 20));
    if (imgio_decode(f->bytes, f->len, path, &img, &ie) < 0)
        return ydoc_fail(&L->d, v, L->e, "file: cannot read texture %s: %s", path, ie.msg);
    if ((*seen = scene_add_image(L->sc, &img)) < 0) {
        image_free(&img);
        return ydoc_fail(&L->d, v, L->e, "out of memory");
    }
    L->texture_bytes += bytes;
    *image = *seen;
    return 0;
}

/* An image texture: `file` relative to the scene file, PNG or PPM, at most
   TEXTURE_MAX_BYTES on disk and TEXTURE_MAX_PIXELS decoded, all of them TEXTURE_BUDGET_BYTES. */
static int load_image(struct scene_parse *L, yaml_node_t *n, struct texture *t)
{
    yaml_node_t *v;
    const char *file;
    if (ymap_check(&L->d, n, image_keys, "image texture", L->e) < 0)
        return -1;
    if (!(v = ymap_get(&L->d, n, "file")))
        return ymap_missing(&L->d, n, "file", L->e, "file: missing in image texture");
    if (yget_string(&L->d, v, "file", &file, L->e) < 0)
        return -1;
    char path[1024];
    const struct scene_src_file *f = scene_src_texture(L->src, L->d.file, file, path, sizeof path);
    struct stat st;
    if (stat(path, &st) < 0 || !S_ISREG(st.st_mode)) {
        const char *kind = fileio_kind(path); /* there, but a FIFO, a device, a folder */
        return kind ? ydoc_fail(&L->d, v, L->e, "file: %s is %s, not an image file", path, kind)
                    : ydoc_fail(&L->d, v, L->e, "file: no texture image at %s", path);
    }
    if (st.st_size > TEXTURE_MAX_BYTES)
        return ydoc_fail(&L->d, v, L->e, "file: %s is %lld bytes, over the texture limit of %d", path,
                         (long long)st.st_size, TEXTURE_MAX_BYTES);
    if (!f)
        return ydoc_fail(&L->d, v, L->e, "file: cannot read texture %s: not read with its scene", path);
    t->type = TEX_IMAGE;
    return image_of_file(L, v, f, path, &t->image);
}

static int load_texture(struct scene_parse *L, yaml_node_t *k, yaml_node_t *n)
{
    const char *type;
    yaml_node_t *tn = ymap_get(&L->d, n, "type");
    if (!tn)
        return ymap_missing(&L->d, n, "type", L->e, "type: missing in texture \"%s\"", yscalar(k));
    if (yget_string(&L->d, tn, "type", &type, L->e) < 0)
        return -1;
    struct texture t = {0};
    int rc;
    if (!strcmp(type, "checker"))
        rc = load_checker(L, n, &t);
    else if (!strcmp(type, "noise"))
        rc = load_noise(L, n, &t);
    else if (!strcmp(type, "image"))
        rc = load_image(L, n, &t);
    else
        return scene_parse_unknown(L, tn, "type: unknown texture type", type, texture_types,
                                   "checker, noise or image");
    if (rc < 0)
        return -1;
    if (scene_add_texture(L->sc, &t) < 0)
        return ydoc_fail(&L->d, n, L->e, "out of memory");
    return 0;
}

static const char *const material_keys[] = {"type", "albedo", "texture", "fuzz", "ior", "emit", NULL};

static int load_material(struct scene_parse *L, yaml_node_t *k, yaml_node_t *n)
{
    if (ymap_check(&L->d, n, material_keys, "material", L->e) < 0)
        return -1;
    const char *type, *s;
    yaml_node_t *tn = ymap_get(&L->d, n, "type"), *v;
    if (!tn)
        return ymap_missing(&L->d, n, "type", L->e, "type: missing in material \"%s\"", yscalar(k));
    if (yget_string(&L->d, tn, "type", &type, L->e) < 0)
        return -1;
    int t = 0;
    while (material_types[t] && strcmp(type, material_types[t]))
        t++;
    if (!material_types[t])
        return scene_parse_unknown(L, tn, "type: unknown material type", type, material_types,
                                   "lambertian, metal, dielectric, light or isotropic");
    struct material m = {.type = t, .texture = -1, .albedo = v3(1, 1, 1), .ior = 1.5};
    const char *allowed = material_takes[t];
    yaml_node_t *kk;
    for (int i = 0; ymap_pair(&L->d, n, i, &kk, &v); i++) {
        const char *name = yscalar(kk);
        if (strcmp(name, "type") && !strstr(allowed, name))
            return ydoc_fail(&L->d, kk, L->e, "%s: not a key of a %s material (it takes: %s)", name, type,
                             allowed);
    }
    if ((v = ymap_get(&L->d, n, "albedo")) && scene_parse_color(L, v, "albedo", &m.albedo) < 0)
        return -1;
    if ((v = ymap_get(&L->d, n, "texture"))) {
        if (ymap_get(&L->d, n, "albedo"))
            return ydoc_fail(&L->d, v, L->e, "texture: give albedo or texture, not both");
        if (yget_string(&L->d, v, "texture", &s, L->e) < 0)
            return -1;
        if ((m.texture = scene_parse_find_name(&L->tex, s)) < 0)
            return scene_parse_no_name(L, v, "texture", s, &L->tex, "textures");
    } else if ((m.type == MAT_LAMBERTIAN || m.type == MAT_ISOTROPIC) && !ymap_get(&L->d, n, "albedo")) {
        return ymap_missing(&L->d, n, "albedo", L->e, "albedo: missing in %s material \"%s\"", type,
                            yscalar(k));
    }
    if (number_in(L, n, "fuzz", 0, 1, 0, "in [0, 1]", &m.fuzz) < 0 ||
        number_in(L, n, "ior", 1, 10, 0, "in [1, 10]", &m.ior) < 0)
        return -1;
    if (m.type == MAT_LIGHT) {
        if (!(v = ymap_get(&L->d, n, "emit")))
            return ymap_missing(&L->d, n, "emit", L->e, "emit: missing in light material \"%s\"", yscalar(k));
        if (scene_parse_color(L, v, "emit", &m.emit) < 0)
            return -1;
    }
    if (scene_add_material(L->sc, &m) < 0)
        return ydoc_fail(&L->d, n, L->e, "out of memory");
    return 0;
}

/* Load a named mapping section (textures or materials). */
static int load_section(struct scene_parse *L, yaml_node_t *sec, const char *what, struct names *nm,
                        int (*one)(struct scene_parse *, yaml_node_t *, yaml_node_t *))
{
    if (!sec)
        return 0;
    if (sec->type != YAML_MAPPING_NODE)
        return ydoc_fail(&L->d, sec, L->e, "%s: must be a mapping of name: {...}", what);
    yaml_node_t *k, *v;
    for (int i = 0; ymap_pair(&L->d, sec, i, &k, &v); i++) {
        const char *name = yscalar(k);
        if (!name || !*name)
            return ydoc_fail(&L->d, k, L->e, "%s: names must be plain strings", what);
        if (scene_parse_find_name(nm, name) >= 0)
            return ydoc_fail(&L->d, k, L->e, "%s: duplicate name \"%.40s\"", what, name);
        if (nm->n >= 256)
            return ydoc_fail(&L->d, k, L->e, "%s: more than 256 entries", what);
        if (v->type != YAML_MAPPING_NODE)
            return ydoc_fail(&L->d, v, L->e, "%s: \"%.40s\" must be a mapping {type: ...}", what, name);
        if (one(L, k, v) < 0)
            return -1;
        nm->name[nm->n++] = name;
    }
    return 0;
}

static const char *const scene_keys[] = {"camera", "background", "textures", "materials", "objects", NULL};

int scene_load_src(const struct scene_src *src, struct scene_file *out, struct err *e)
{
    if (!src->parsed) {
        *e = src->parse_err;
        return -1;
    }
    /* the parsed document borrowed (read, never freed here): a retried render loads it again */
    struct scene_parse L = {.d = src->doc, .src = src, .e = e};
    const char *path = src->doc.file;
    memset(out, 0, sizeof *out);
    int rc = -1;
    L.d.max_abs = SCENE_MAX_ABS;
    if (!(L.sc = scene_new()) ||
        (src->n_files && !(L.file_image = malloc((size_t)src->n_files * sizeof *L.file_image)))) {
        err_set(e, path, 0, 0, "out of memory");
        goto done;
    }
    for (int i = 0; i < src->n_files; i++)
        L.file_image[i] = -1;
    yaml_node_t *root = ydoc_root(&L.d), *v;
    if (ymap_check(&L.d, root, scene_keys, "scene", e) < 0)
        goto done;
    if (!(v = ymap_get(&L.d, root, "camera"))) {
        ymap_missing(&L.d, root, "camera", e, "camera: missing in scene");
        goto done;
    }
    if (load_camera(&L, v, out) < 0)
        goto done;
    L.cam = &out->camera;
    if ((v = ymap_get(&L.d, root, "background")) &&
        scene_parse_color(&L, v, "background", &L.sc->background) < 0)
        goto done;
    if (load_section(&L, ymap_get(&L.d, root, "textures"), "textures", &L.tex, load_texture) < 0 ||
        load_section(&L, ymap_get(&L.d, root, "materials"), "materials", &L.mat, load_material) < 0)
        goto done;
    if (scene_objects_load(&L, ymap_get(&L.d, root, "objects"), root) < 0)
        goto done;
    if (scene_finish(L.sc, e) < 0) {
        e->line = 0;
        snprintf(e->file, sizeof e->file, "%s", path);
        goto done;
    }
    scene_parse_facing_away(&L, out->warning, sizeof out->warning);
    out->scene = L.sc;
    L.sc = NULL;
    rc = 0;
done:
    free(L.light_pos);
    free(L.file_image);
    scene_free(L.sc);
    return rc;
}

int scene_load(const char *path, struct scene_file *out, struct err *e)
{
    struct scene_src src;
    uint64_t h = 0;
    memset(out, 0, sizeof *out);
    int rc = scene_src_read(path, &src, &h, e) < 0 ? -1 : scene_load_src(&src, out, e);
    scene_src_free(&src);
    return rc;
}

void scene_file_free(struct scene_file *sf)
{
    scene_free(sf->scene);
    sf->scene = NULL;
}
