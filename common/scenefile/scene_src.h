/* scene_src: a scene file read once: its YAML parsed and its image textures' bytes, kept for as
   many loads (scene_load_src) as the renders want, and the hash of all it read. */
#ifndef SCENE_SRC_H
#define SCENE_SRC_H

#include <stddef.h>
#include <stdint.h>

#include "base/err.h"
#include "yamlx.h"

/* An image texture's file, read once with its scene (scene_src_read). */
struct scene_src_file {
    char path[1024]; /* beside the scene file unless absolute */
    uint8_t *bytes;  /* NULL: unreadable, read_err says why (scene_load_src reports it) */
    size_t len;
    struct err read_err;
    int same_as;       /* -1, or an earlier entry's index: the same file by another path */
    uint64_t dev, ino; /* which file it is (0, 0 when stat failed) */
};

/* A scene file read once (scene_src_read): its YAML parsed, and its image textures' bytes, kept
   until scene_src_free. */
struct scene_src {
    struct ydoc doc; /* doc.file: the scene file's path */
    int parsed;      /* 0: the YAML did not parse, parse_err says why (scene_load_src reports it) */
    struct err parse_err;
    struct scene_src_file *files; /* one per image texture named, n_files of them */
    int n_files;
    size_t texture_budget; /* the decoded textures' limit in bytes: TEXTURE_BUDGET_BYTES (tests lower it) */
};

/* Read the scene file at path once: fold into *h what a render of it reads (the file's bytes,
   then the bytes of each image texture it names, so a changed texture makes outputs stale) and
   parse it into src, the textures' bytes kept there for scene_load_src (each file read once). 0,
   or -1 with e when the file cannot be read; a scene that does not parse, or a texture that
   cannot be read, adds nothing to *h (scene_load_src reports those). Free src with
   scene_src_free either way. */
int scene_src_read(const char *path, struct scene_src *src, uint64_t *h, struct err *e);
void scene_src_free(struct scene_src *src);

/* The image texture file `file` (as a scene file at scene names it) in src, its resolved path
   in path (n bytes: beside the scene file unless absolute): the entry that holds its bytes (the
   first path read to that file). NULL when src did not read it. */
const struct scene_src_file *scene_src_texture(const struct scene_src *src, const char *scene,
                                               const char *file, char *path, size_t n);

#endif
