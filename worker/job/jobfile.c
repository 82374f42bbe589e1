/* jobfile: one read and one parse of a job file, and what is derived from it. */
#include "jobfile.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fileio.h"
#include "base/hash.h"
#include "image/imgio.h"

/* The parsed document's kind: a mapping with studies: is a suite, with variants: a compare job
   (either written null still says which); anything else a plain job, its reader says what's wrong. */
static enum jobfile_kind kind_of(struct ydoc *d)
{
    yaml_node_t *root = ydoc_root(d);
    if (!root || root->type != YAML_MAPPING_NODE)
        return JOBFILE_PLAIN;
    return ymap_get_raw(d, root, "studies")    ? JOBFILE_SUITE
           : ymap_get_raw(d, root, "variants") ? JOBFILE_COMPARE
                                               : JOBFILE_PLAIN;
}

/* Read the file once, hash and parse it, and tell its kind. 0 or -1 with e. */
static int read_parse(struct jobfile *f, const char *from, const char *path, struct err *e)
{
    memset(f, 0, sizeof *f);
    snprintf(f->path, sizeof f->path, "%s", path);
    if (fileio_read_all(from, YDOC_MAX_BYTES, &f->bytes, &f->len, e) < 0) {
        if (strcmp(e->file, from) == 0)
            snprintf(e->file, sizeof e->file, "%s", path);
        return -1;
    }
    f->hash = hash_bytes(HASH_FNV_OFFSET, f->bytes, f->len);
    if (ydoc_parse(&f->doc, path, f->bytes, f->len, e) < 0)
        return -1;
    f->kind = kind_of(&f->doc);
    return 0;
}

enum jobfile_kind jobfile_peek_kind(const char *from)
{
    struct jobfile f;
    struct err ignored;
    (void)read_parse(&f, from, from, &ignored);
    enum jobfile_kind kind = f.kind;
    jobfile_close(&f);
    return kind;
}

int jobfile_open(struct jobfile *f, const char *from, const char *path, struct err *e)
{
    if (read_parse(f, from, path, e) < 0)
        return -1;
    if (f->kind != JOBFILE_PLAIN)
        return 0;
    struct job *j = &f->job;
    if (job_from_doc(&f->doc, path, j, e) < 0)
        return -1;
    j->hash = f->hash;
    if (scene_src_read(j->scene_path, &f->scene, &j->hash, e) < 0)
        return -1;
    /* The reference's bytes too, kept for the render to score against: a replaced reference must
       not leave a sidecar's old error figures current. Unreadable: run_load_reference says so. */
    struct err ignored;
    if (j->reference[0] &&
        fileio_read_all(j->reference, IMGIO_MAX_BYTES, &f->ref_bytes, &f->ref_len, &ignored) == 0)
        j->hash = hash_bytes(j->hash, f->ref_bytes, f->ref_len);
    return 0;
}

void jobfile_close(struct jobfile *f)
{
    free(f->bytes);
    f->bytes = NULL;
    free(f->ref_bytes);
    f->ref_bytes = NULL;
    ydoc_free(&f->doc);
    scene_src_free(&f->scene);
}
