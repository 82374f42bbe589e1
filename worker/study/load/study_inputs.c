/* study_inputs: a study's input files, each read once and kept. */
#include "study_inputs.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fileio.h"
#include "base/hash.h"
#include "image/imgio.h"

struct study_inputs *study_inputs_new(void)
{
    return calloc(1, sizeof(struct study_inputs));
}

void study_inputs_free(struct study_inputs *in)
{
    if (!in)
        return;
    for (int i = 0; i < in->n_scenes; i++) {
        scene_src_free(&in->scenes[i]->src);
        free(in->scenes[i]);
    }
    for (int i = 0; i < in->n_refs; i++) {
        study_ref_free(in->refs[i]);
        free(in->refs[i]);
    }
    free(in->scenes);
    free(in->refs);
    free(in);
}

/* The capacity after cap when n entries fill it: doubled (from 8), or cap while there is room. */
static int room(int n, int cap)
{
    return n < cap ? cap : cap ? 2 * cap : 8;
}

const struct study_scene *study_inputs_scene(struct study_inputs *in, const char *path, struct err *e)
{
    for (int i = 0; i < in->n_scenes; i++)
        if (!strcmp(in->scenes[i]->path, path))
            return in->scenes[i];
    int cap = room(in->n_scenes, in->cap_scenes);
    struct study_scene *s = calloc(1, sizeof *s), **more = realloc(in->scenes, (size_t)cap * sizeof *more);
    if (more)
        in->scenes = more, in->cap_scenes = cap;
    if (!s || !more) {
        free(s);
        err_set(e, path, 0, 0, "out of memory");
        return NULL;
    }
    snprintf(s->path, sizeof s->path, "%s", path);
    s->hash = HASH_FNV_OFFSET;
    if (scene_src_read(path, &s->src, &s->hash, e) < 0) {
        scene_src_free(&s->src);
        free(s);
        return NULL;
    }
    in->scenes[in->n_scenes++] = s;
    return s;
}

const struct study_ref *study_inputs_find_ref(const struct study_inputs *in, const char *path,
                                              uint64_t scene_hash)
{
    for (int i = 0; i < in->n_refs; i++)
        if (in->refs[i]->scene_hash == scene_hash && !strcmp(in->refs[i]->path, path))
            return in->refs[i];
    return NULL;
}

const struct study_ref *study_inputs_keep_ref(struct study_inputs *in, struct study_ref *r, struct err *e)
{
    int cap = room(in->n_refs, in->cap_refs);
    struct study_ref *kept = malloc(sizeof *kept), **more = realloc(in->refs, (size_t)cap * sizeof *more);
    if (more)
        in->refs = more, in->cap_refs = cap;
    if (!kept || !more) {
        free(kept);
        study_ref_free(r);
        err_set(e, NULL, 0, 0, "out of memory");
        return NULL;
    }
    *kept = *r;
    r->f = (struct rgbf){0};
    r->display = (struct rgb8){0};
    in->refs[in->n_refs++] = kept;
    return kept;
}

int study_ref_decode(struct study_ref *r, const char *path, uint64_t scene_hash, const uint8_t *data,
                     size_t len, struct err *e)
{
    study_ref_free(r);
    snprintf(r->path, sizeof r->path, "%s", path);
    r->scene_hash = scene_hash;
    r->hash = hash_bytes(scene_hash, data, len);
    if (imgio_decode_f(data, len, path, &r->f, &r->domain, e) < 0 ||
        (r->domain == IMG_DISPLAY8 ? imgio_decode(data, len, path, &r->display, e)
                                   : image_alloc(&r->display, r->f.w, r->f.h, e)) < 0) {
        study_ref_free(r);
        return -1;
    }
    if (r->domain == IMG_LINEAR)
        image_float_to_rgb8(r->f.px, r->f.w, r->f.h, r->display.px);
    return 0;
}

void study_ref_free(struct study_ref *r)
{
    image_f_free(&r->f);
    image_free(&r->display);
}

uint64_t study_inputs_program_hash(struct study_inputs *in)
{
    if (!in->program_hash) {
        struct err ignored; /* unreadable: the key lacks it */
        in->program_hash = HASH_FNV_OFFSET;
        fileio_hash("/proc/self/exe", 1u << 30, &in->program_hash, &ignored);
    }
    return in->program_hash;
}
