/* compare_mask: `mask: { rect: [...] }` or `mask: { image: FILE }` into a scene's pixel mask. */
#include "compare_mask.h"

#include <stdlib.h>
#include <string.h>

#include "image/imgio.h"
#include "job/job_path.h"
#include "scenefile/yget.h"

int compare_mask_item(struct ydoc *d, yaml_node_t *item, yaml_node_t **scene, yaml_node_t **mask,
                      struct err *e)
{
    static const char *const keys[] = {"scene", "mask", NULL};
    *scene = item, *mask = NULL;
    if (!item || item->type != YAML_MAPPING_NODE)
        return 0;
    if (ymap_check(d, item, keys, "scenes item", e) < 0)
        return -1;
    if (!(*scene = ymap_get(d, item, "scene")))
        return ymap_missing(
            d, item, "scene", e,
            "scenes: an item that is a mapping needs scene:, e.g. { scene: cornell, mask: { rect: "
            "[0, 0, 32, 32] } }");
    *mask = ymap_get(d, item, "mask");
    return 0;
}

static int load_rect(struct ydoc *d, yaml_node_t *r, struct compare_scene *cs, struct img_mask *out,
                     struct err *e)
{
    long rect[4];
    if (yseq_len(r) != 4)
        return ydoc_fail(d, r, e, "mask: rect: must be a list of 4 whole numbers [x0, y0, x1, y1], got %s%s",
                         ydoc_node_kind(r), yseq_len(r) >= 0 ? " of another length" : "");
    for (int i = 0; i < 4; i++)
        if (yget_long(d, yseq_item(d, r, i), "mask: rect", -(1L << 30), 1L << 30, &rect[i], e) < 0)
            return -1;
    if (mask_rect(out, cs->width, cs->height, rect, e) < 0)
        return ydoc_fail(d, r, e, "mask: rect: %s (scene %s)", e->msg, cs->name);
    return 0;
}

static int load_image(struct ydoc *d, yaml_node_t *v, const char *job_path, struct compare_scene *cs,
                      struct img_mask *out, struct err *e)
{
    const char *name;
    char path[JOB_PATH_MAX];
    struct rgb8 img = {0};
    if (yget_string(d, v, "mask: image", &name, e) < 0)
        return -1;
    job_path_resolve(job_path, name, path, sizeof path);
    int rc = imgio_read(path, &img, e) < 0 || mask_from_image(out, &img, e) < 0 ? -1 : 0;
    image_free(&img);
    if (rc < 0)
        return ydoc_fail(d, v, e, "mask: image: %s: %s", path, e->msg);
    if (mask_check_size(out, cs->width, cs->height, e) < 0) {
        mask_free(out);
        return ydoc_fail(d, v, e, "mask: image: %s: %s (scene %s)", path, e->msg, cs->name);
    }
    return 0;
}

int compare_mask_load(struct ydoc *d, yaml_node_t *m, const char *job_path, struct compare_scene *cs,
                      struct err *e)
{
    static const char *const keys[] = {"rect", "image", NULL};
    if (!m)
        return 0;
    if (m->type != YAML_MAPPING_NODE)
        return ydoc_fail(d, m, e, "mask: must be { rect: [x0, y0, x1, y1] } or { image: FILE.png }, got %s",
                         ydoc_node_kind(m));
    if (ymap_check(d, m, keys, "mask", e) < 0)
        return -1;
    yaml_node_t *rect = ymap_get(d, m, "rect"), *image = ymap_get(d, m, "image");
    if ((rect != NULL) == (image != NULL))
        return ydoc_fail(d, m, e, "mask: give rect: [x0, y0, x1, y1] or image: FILE.png (one of them)");
    struct img_mask *mask = calloc(1, sizeof *mask);
    if (!mask)
        return err_set(e, d->file, 0, 0, "out of memory");
    if ((rect ? load_rect(d, rect, cs, mask, e) : load_image(d, image, job_path, cs, mask, e)) < 0) {
        free(mask);
        return -1;
    }
    mask_free(cs->mask);
    free(cs->mask);
    cs->mask = mask;
    return 0;
}
