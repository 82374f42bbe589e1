/* part: encoding, decoding and merging the part files of `worker JOB --part I/N` and `merge`. */
#include "part.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "base/fileio.h"
#include "base/hash.h"
#include "outdir.h"
#include "run_out.h"

#define PART_MAGIC "WPART\r\n\x1a" /* 8 bytes; the CR LF catch text-mode mangling, as PNG's do */
#define PART_HEADER 120            /* bytes before the rows */

struct part_header {
    uint32_t version, width, height, part, parts, processes;
    uint64_t hash;
    struct render_stats st;
    double wall_s, cpu_s;
    uint64_t peak_rss_kb;
};

uint64_t part_hash(const struct job *j)
{
    uint64_t h = hash_u64(j->hash, PART_VERSION);
    return hash_bytes(h, WORKER_VERSION, strlen(WORKER_VERSION));
}

static int part_rows(int h, int part, int parts)
{
    return h > part ? (h - part + parts - 1) / parts : 0;
}

static uint8_t *put_u32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        *p++ = (uint8_t)(v >> (8 * i));
    return p;
}

static uint8_t *put_u64(uint8_t *p, uint64_t v)
{
    for (int i = 0; i < 8; i++)
        *p++ = (uint8_t)(v >> (8 * i));
    return p;
}

static uint8_t *put_f64(uint8_t *p, double d)
{
    uint64_t v;
    memcpy(&v, &d, sizeof v);
    return put_u64(p, v);
}

static uint32_t get_u32(const uint8_t **p)
{
    uint32_t v = 0;
    for (int i = 0; i < 4; i++)
        v |= (uint32_t)(*p)[i] << (8 * i);
    *p += 4;
    return v;
}

static uint64_t get_u64(const uint8_t **p)
{
    uint64_t v = 0;
    for (int i = 0; i < 8; i++)
        v |= (uint64_t)(*p)[i] << (8 * i);
    *p += 8;
    return v;
}

static double get_f64(const uint8_t **p)
{
    uint64_t v = get_u64(p);
    double d;
    memcpy(&d, &v, sizeof d);
    return d;
}

static void encode_header(uint8_t *b, const struct part_header *h)
{
    memcpy(b, PART_MAGIC, 8);
    uint8_t *p = b + 8;
    p = put_u32(p, h->version);
    p = put_u32(p, h->width);
    p = put_u32(p, h->height);
    p = put_u32(p, h->part);
    p = put_u32(p, h->parts);
    p = put_u32(p, h->processes);
    p = put_u64(p, h->hash);
    p = put_u64(p, h->st.pixels);
    p = put_u64(p, h->st.samples);
    p = put_u64(p, h->st.rays);
    p = put_u64(p, h->st.light_sets);
    p = put_u64(p, h->st.nonfinite);
    p = put_u32(p, h->st.spp_min);
    p = put_u32(p, h->st.spp_max);
    p = put_f64(p, h->st.sampler_s);
    p = put_f64(p, h->wall_s);
    p = put_f64(p, h->cpu_s);
    put_u64(p, h->peak_rss_kb);
}

/* Decode and check the header of a part file of len bytes: magic, version, a sane split and a
   length that matches the rows it claims. 0 or -1 with e filled (file = path). */
static int decode_header(const uint8_t *b, size_t len, const char *path, struct part_header *h, struct err *e)
{
    if (len < PART_HEADER || memcmp(b, PART_MAGIC, 8) != 0)
        return err_set(e, path, 0, 0, "not a worker part file");
    const uint8_t *p = b + 8;
    h->version = get_u32(&p);
    h->width = get_u32(&p);
    h->height = get_u32(&p);
    h->part = get_u32(&p);
    h->parts = get_u32(&p);
    h->processes = get_u32(&p);
    h->hash = get_u64(&p);
    h->st.pixels = get_u64(&p);
    h->st.samples = get_u64(&p);
    h->st.rays = get_u64(&p);
    h->st.light_sets = get_u64(&p);
    h->st.nonfinite = get_u64(&p);
    h->st.spp_min = get_u32(&p);
    h->st.spp_max = get_u32(&p);
    h->st.sampler_s = get_f64(&p);
    h->wall_s = get_f64(&p);
    h->cpu_s = get_f64(&p);
    h->peak_rss_kb = get_u64(&p);
    if (h->version != PART_VERSION)
        return err_set(e, path, 0, 0, "part file version %u, this worker reads version %d", h->version,
                       PART_VERSION);
    if (h->width < 1 || h->width > IMAGE_MAX_SIDE || h->height < 1 || h->height > IMAGE_MAX_SIDE ||
        h->parts < 1 || h->parts > PART_MAX || h->part >= h->parts ||
        (uint64_t)h->width * h->height > IMAGE_MAX_PIXELS)
        return err_set(e, path, 0, 0, "damaged part file (impossible size or split)");
    size_t want =
        PART_HEADER + (size_t)part_rows((int)h->height, (int)h->part, (int)h->parts) * h->width * 12 + 4;
    if (len != want)
        return err_set(e, path, 0, 0, "damaged part file: %zu bytes, expected %zu", len, want);
    return 0;
}

int part_write(const char *path, const struct job *j, int w, int h, int part, int parts, const float *rgb,
               const struct procs_result *fr, struct err *e)
{
    size_t rows = (size_t)part_rows(h, part, parts);
    size_t len = PART_HEADER + rows * (size_t)w * 12 + 4;
    uint8_t *buf = malloc(len);
    if (!buf)
        return err_set(e, NULL, 0, 0, "cannot write %s: out of memory", path);
    struct part_header hd = {PART_VERSION,
                             (uint32_t)w,
                             (uint32_t)h,
                             (uint32_t)part,
                             (uint32_t)parts,
                             (uint32_t)fr->processes,
                             part_hash(j),
                             fr->total,
                             fr->wall_s,
                             fr->cpu_s,
                             (uint64_t)(fr->peak_rss_kb > 0 ? fr->peak_rss_kb : 0)};
    encode_header(buf, &hd);
    uint8_t *p = buf + PART_HEADER;
    for (int y = part; y < h; y += parts)
        for (size_t i = 0; i < (size_t)w * 3; i++) {
            uint32_t v;
            memcpy(&v, &rgb[(size_t)y * w * 3 + i], sizeof v);
            p = put_u32(p, v);
        }
    put_u32(p, (uint32_t)crc32(0L, buf, (uInt)(len - 4)));
    int rc = fileio_write_atomic(path, buf, len, e);
    free(buf);
    return rc;
}

/* Read the part file at path whole and check it: header, length and checksum. The caller frees
 *data. 0 or -1 with e filled. */
static int read_part(const char *path, uint8_t **data, size_t *len, struct part_header *h, struct err *e)
{
    if (fileio_read_all(path, (size_t)IMAGE_MAX_PIXELS * 12 + PART_HEADER + 4, data, len, e) < 0)
        return -1;
    if (decode_header(*data, *len, path, h, e) < 0)
        return -1;
    const uint8_t *p = *data + *len - 4;
    if (get_u32(&p) != (uint32_t)crc32(0L, *data, (uInt)(*len - 4)))
        return err_set(e, path, 0, 0, "damaged part file: checksum mismatch");
    return 0;
}

int part_matches(const char *path, const struct job *j, int part, int parts)
{
    uint8_t *data = NULL;
    size_t len;
    struct part_header h;
    struct err e;
    int ok = read_part(path, &data, &len, &h, &e) == 0 && h.hash == part_hash(j) && (int)h.part == part &&
             (int)h.parts == parts;
    free(data);
    return ok;
}

/* The split N of the part files of j in dir: -1 with e filled when there are none or parts of
   several splits lie side by side. */
static int find_split(const struct job *j, const char *dir, struct err *e)
{
    DIR *d = opendir(dir);
    if (!d)
        return err_set(e, j->path, 0, 0,
                       "no part files to merge: cannot open %s (render them first with "
                       "worker %s --part I/N)",
                       dir, j->path);
    int split = 0, other = 0;
    struct dirent *de;
    while ((de = readdir(d))) {
        int i, n;
        if (!outdir_part_name(j, de->d_name, &i, &n))
            continue;
        if (!split)
            split = n;
        else if (n != split)
            other = n;
    }
    closedir(d);
    if (!split)
        return err_set(e, j->path, 0, 0,
                       "no part files to merge in %s (render them first with worker %s --part "
                       "I/N)",
                       dir, j->path);
    if (other)
        return err_set(e, j->path, 0, 0, "parts of two splits in %s (of %d and of %d): remove the stale ones",
                       dir, split < other ? split : other, split < other ? other : split);
    return split;
}

/* Read part `part` of `parts` for j into rgb (allocated on the first part, w x h from it) and
   its stats into fr->proc[part]. 0 or -1 with e filled. */
static int merge_one(const struct job *j, const char *path, int part, int parts, float **rgb, int *w, int *h,
                     struct procs_result *fr, struct err *e)
{
    uint8_t *data = NULL;
    size_t len;
    struct part_header hd;
    int rc = -1;
    if (read_part(path, &data, &len, &hd, e) < 0)
        goto done;
    if ((int)hd.part != part || (int)hd.parts != parts) {
        err_set(e, path, 0, 0, "holds part %u of %u, expected part %d of %d", hd.part, hd.parts, part, parts);
        goto done;
    }
    if (hd.hash != part_hash(j)) {
        err_set(e, path, 0, 0,
                "rendered from other inputs (the job file, its scene or the worker version "
                "changed): render this part again");
        goto done;
    }
    if (!*rgb) {
        *w = (int)hd.width;
        *h = (int)hd.height;
        if (!(*rgb = calloc((size_t)*w * *h * 3, sizeof **rgb))) {
            err_set(e, NULL, 0, 0, "out of memory merging %dx%d parts", *w, *h);
            goto done;
        }
    } else if ((int)hd.width != *w || (int)hd.height != *h) {
        err_set(e, path, 0, 0, "is %ux%u but the other parts are %dx%d", hd.width, hd.height, *w, *h);
        goto done;
    }
    const uint8_t *p = data + PART_HEADER;
    for (int y = part; y < *h; y += parts)
        for (size_t i = 0; i < (size_t)*w * 3; i++) {
            uint32_t v = get_u32(&p);
            memcpy(&(*rgb)[(size_t)y * *w * 3 + i], &v, sizeof v);
        }
    fr->proc[part] = (struct procs_proc){hd.st, hd.wall_s, hd.cpu_s, 1};
    render_stats_add(&fr->total, &hd.st);
    fr->wall_s += hd.wall_s;
    fr->cpu_s += hd.cpu_s;
    if ((long)hd.peak_rss_kb > fr->peak_rss_kb)
        fr->peak_rss_kb = (long)hd.peak_rss_kb;
    rc = 0;
done:
    free(data);
    return rc;
}

int part_merge(const struct job *j, const struct run_opts *o, struct run_result *rr, struct err *e)
{
    char dir[2048], path[2048], missing[512] = "";
    struct procs_result *fr = calloc(1, sizeof *fr);
    struct rgb8 ref = {0};
    float *rgb = NULL;
    int rc = 2, w = 0, h = 0, nmissing = 0;
    memset(rr, 0, sizeof *rr);
    if (!fr) {
        err_set(e, NULL, 0, 0, "out of memory");
        return 1;
    }
    outdir_dir(o->out_dir, j->name, dir, sizeof dir);
    int parts = find_split(j, dir, e);
    if (parts < 0)
        goto done;
    for (int i = 0; i < parts; i++) {
        outdir_part_path(j, o->out_dir, i, parts, path, sizeof path);
        FILE *f = fopen(path, "rb");
        if (f) {
            fclose(f);
            continue;
        }
        size_t l = strlen(missing);
        if (l + 16 < sizeof missing)
            snprintf(missing + l, sizeof missing - l, "%s%d", nmissing ? ", " : "", i);
        nmissing++;
    }
    if (nmissing) {
        err_set(e, j->path, 0, 0, "cannot merge: missing part%s %s of %d in %s", nmissing > 1 ? "s" : "",
                missing, parts, dir);
        goto done;
    }
    render_stats_init(&fr->total);
    fr->processes = parts;
    for (int i = 0; i < parts; i++) {
        outdir_part_path(j, o->out_dir, i, parts, path, sizeof path);
        if (merge_one(j, path, i, parts, &rgb, &w, &h, fr, e) < 0)
            goto done;
    }
    rr->width = w;
    rr->height = h;
    if (run_load_reference(j, w, h, &ref, e) < 0)
        goto done;
    rr->farm = *fr;
    rc = run_out_write(j, o, rgb, w, h, fr, &ref, parts, rr, e) < 0 ? 1 : 0;
done:
    image_free(&ref);
    free(rgb);
    free(fr);
    return rc;
}
