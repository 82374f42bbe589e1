/* scene_src: reading a scene file and its image textures, once. */
#include "scene_src.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/fileio.h"
#include "base/hash.h"
#include "scene_parse.h"

/* path, set to where an image texture's `file` is: beside the scene file unless absolute. */
static const char *texture_path(const char *scene, const char *file, char *path, size_t n)
{
    const char *slash = strrchr(scene, '/');
    if (file[0] == '/' || !slash)
        snprintf(path, n, "%s", file);
    else
        snprintf(path, n, "%.*s/%s", (int)(slash - scene), scene, file);
    return path;
}

const struct scene_src_file *scene_src_texture(const struct scene_src *src, const char *scene,
                                               const char *file, char *path, size_t n)
{
    texture_path(scene, file, path, n);
    for (int i = 0; i < src->n_files; i++)
        if (!strcmp(src->files[i].path, path))
            return src->files[i].same_as < 0 ? &src->files[i] : &src->files[src->files[i].same_as];
    return NULL;
}

int scene_src_read(const char *path, struct scene_src *src, uint64_t *h, struct err *e)
{
    uint8_t *data;
    size_t len;
    memset(src, 0, sizeof *src);
    src->texture_budget = TEXTURE_BUDGET_BYTES;
    if (fileio_read_all(path, YDOC_MAX_BYTES, &data, &len, e) < 0)
        return -1;
    *h = hash_bytes(*h, data, len);
    src->parsed = ydoc_parse(&src->doc, path, data, len, &src->parse_err) == 0;
    free(data);
    struct ydoc *d = &src->doc;
    yaml_node_t *textures = src->parsed ? ymap_get(d, ydoc_root(d), "textures") : NULL, *k, *v;
    int n = 0;
    size_t total = 0; /* the texture files' bytes read */
    for (int i = 0; textures && ymap_pair(d, textures, i, &k, &v); i++)
        n++;
    if (n && !(src->files = calloc((size_t)n, sizeof *src->files)))
        return err_set(e, path, 0, 0, "out of memory");
    for (int i = 0; textures && ymap_pair(d, textures, i, &k, &v); i++) {
        const char *t = yscalar(ymap_get(d, v, "type")), *f = yscalar(ymap_get(d, v, "file"));
        if (!t || !f || strcmp(t, "image"))
            continue;
        struct scene_src_file *sf = &src->files[src->n_files];
        texture_path(path, f, sf->path, sizeof sf->path);
        const struct scene_src_file *seen = NULL; /* a file two textures name: read once */
        for (int j = 0; j < src->n_files && !seen; j++)
            seen = strcmp(src->files[j].path, sf->path) ? NULL : &src->files[j];
        if (seen) {
            if (seen->bytes)
                *h = hash_bytes(*h, seen->bytes, seen->len);
            continue;
        }
        src->n_files++;
        sf->same_as = -1;
        struct stat st;
        if (stat(sf->path, &st) == 0) { /* another path to a file already read ("./a.png"): its bytes */
            sf->dev = (uint64_t)st.st_dev;
            sf->ino = (uint64_t)st.st_ino;
            for (int j = 0; j < src->n_files - 1 && sf->same_as < 0; j++)
                if (src->files[j].same_as < 0 && src->files[j].ino == sf->ino && src->files[j].dev == sf->dev)
                    sf->same_as = j;
        }
        if (sf->same_as >= 0) {
            if (src->files[sf->same_as].bytes)
                *h = hash_bytes(*h, src->files[sf->same_as].bytes, src->files[sf->same_as].len);
            continue;
        }
        /* unreadable, or over the scene's budget: scene_load_src says so */
        if (fileio_read_all(sf->path, TEXTURE_MAX_BYTES, &sf->bytes, &sf->len, &sf->read_err) < 0)
            continue;
        if (sf->len > TEXTURE_BUDGET_BYTES - total) {
            err_set(&sf->read_err, sf->path, 0, 0, "the scene's texture files come to over %zu MiB together",
                    TEXTURE_BUDGET_BYTES >> 20);
            free(sf->bytes);
            sf->bytes = NULL;
            continue;
        }
        total += sf->len;
        *h = hash_bytes(*h, sf->bytes, sf->len);
    }
    return 0;
}

void scene_src_free(struct scene_src *src)
{
    ydoc_free(&src->doc);
    for (int i = 0; i < src->n_files; i++)
        free(src->files[i].bytes);
    free(src->files);
    src->files = NULL;
    src->n_files = 0;
}
