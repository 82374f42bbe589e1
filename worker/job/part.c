/* part: encoding and decoding the part files of `worker JOB --part I/N` (merged by farm/merge.c). */
#include "part.h"

#include <fcntl.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#include "base/fileio.h"
#include "base/hash.h"

#define PART_MAGIC "WPART\r\n\x1a" /* 8 bytes; the CR LF catch text-mode mangling, as PNG's do */
#define PART_HEADER 160            /* bytes before the rows */

uint64_t part_hash(const struct job *j)
{
    uint64_t h = hash_u64(j->hash, PART_VERSION);
    return hash_bytes(h, WORKER_VERSION, strlen(WORKER_VERSION));
}

static int part_rows(int h, int part, int parts)
{
    return h > part ? (h - part + parts - 1) / parts : 0;
}

/* v's low n bytes at p, little-endian; returns p past them. */
static uint8_t *put_le(uint8_t *p, uint64_t v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        *p++ = (uint8_t)(v >> (8 * i));
    return p;
}

/* The n bytes at *p as a little-endian number; *p advanced past them. */
static uint64_t get_le(const uint8_t **p, size_t n)
{
    uint64_t v = 0;
    for (size_t i = 0; i < n; i++)
        v |= (uint64_t)(*p)[i] << (8 * i);
    *p += n;
    return v;
}

/* The header's fields after the magic, in file order (part.h's layout): each little-endian, a u32
   or a u64 (a double as its bits) as its field in struct part_header. The writer and the reader
   both walk it. */
#define AT(f) offsetof(struct part_header, f)
static const struct {
    size_t at, size;
} header_fields[] = {{AT(version), 4},
                     {AT(width), 4},
                     {AT(height), 4},
                     {AT(part), 4},
                     {AT(parts), 4},
                     {AT(processes), 4},
                     {AT(hash), 8},
                     {AT(st.pixels), 8},
                     {AT(st.samples), 8},
                     {AT(st.rays), 8},
                     {AT(st.light_sets), 8},
                     {AT(st.nonfinite), 8},
                     {AT(st.spp_min), 4},
                     {AT(st.spp_max), 4},
                     {AT(st.sampler_s), 8},
                     {AT(wall_s), 8},
                     {AT(cpu_s), 8},
                     {AT(peak_rss_kb), 8},
                     {AT(st.shadow_rays), 8},
                     {AT(st.pixel_points), 8},
                     {AT(st.light_points), 8},
                     {AT(st.padded_points), 8},
                     {AT(st.padded_sets), 8}};
#define N_HEADER_FIELDS (sizeof header_fields / sizeof header_fields[0])

static void encode_header(uint8_t *b, const struct part_header *h)
{
    memcpy(b, PART_MAGIC, 8);
    b += 8;
    for (size_t i = 0; i < N_HEADER_FIELDS; i++) {
        const size_t n = header_fields[i].size;
        uint32_t u = 0;
        uint64_t v = 0;
        memcpy(n == 4 ? (void *)&u : (void *)&v, (const char *)h + header_fields[i].at, n);
        b = put_le(b, n == 4 ? u : v, n);
    }
}

/* Bytes of the part file whose header is h: header, its rows, CRC. */
static size_t part_bytes(const struct part_header *h)
{
    return PART_HEADER + (size_t)part_rows((int)h->height, (int)h->part, (int)h->parts) * h->width * 12 + 4;
}

/* Decode and check the header of a part file of len bytes: magic, version, a sane size and
   split (part_read checks the length against it). 0 or -1 with e filled (file = path). */
static int decode_header(const uint8_t *b, size_t len, const char *path, struct part_header *h, struct err *e)
{
    if (len < PART_HEADER || memcmp(b, PART_MAGIC, 8) != 0)
        return err_set(e, path, 0, 0, "not a worker part file");
    const uint8_t *p = b + 8;
    for (size_t i = 0; i < N_HEADER_FIELDS; i++) {
        const size_t n = header_fields[i].size;
        uint64_t v = get_le(&p, n);
        uint32_t u = (uint32_t)v;
        memcpy((char *)h + header_fields[i].at, n == 4 ? (void *)&u : (void *)&v, n);
    }
    if (h->version != PART_VERSION)
        return err_set(e, path, 0, 0,
                       "a part file of another worker version (part format %u; this worker reads format %d): "
                       "render this part again with this worker",
                       h->version, PART_VERSION);
    /* the sides a render allows, not a decoder's IMAGE_MAX_PIXELS: parts of a 10240x10240 render
       (1.05e8 pixels) were refused as damaged, and --part resume never saw them as current */
    if (h->width < 1 || h->width > IMAGE_MAX_SIDE || h->height < 1 || h->height > IMAGE_MAX_SIDE ||
        h->parts < 1 || h->parts > PART_MAX || h->part >= h->parts)
        return err_set(e, path, 0, 0, "damaged part file (impossible size or split)");
    return 0;
}

int part_write(const char *path, const struct job *j, const struct part_frame *fb, int part, int parts,
               const struct procs_result *fr, struct err *e)
{
    int w = fb->w, h = fb->h;
    const float *rgb = fb->rgb;
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
    const size_t len = part_bytes(&hd);
    uint8_t *buf = malloc(len);
    if (!buf)
        return err_set(e, NULL, 0, 0, "cannot write %s: out of memory", path);
    encode_header(buf, &hd);
    uint8_t *p = buf + PART_HEADER;
    for (int y = part; y < h; y += parts)
        for (size_t i = 0; i < (size_t)w * 3; i++) {
            uint32_t v;
            memcpy(&v, &rgb[(size_t)y * w * 3 + i], sizeof v);
            p = put_le(p, v, 4);
        }
    put_le(p, crc32(0L, buf, (uInt)(len - 4)), 4);
    int rc = fileio_write_atomic(path, buf, len, e);
    free(buf);
    return rc;
}

/* Counters within 2^56, so that the sum of PART_MAX parts cannot wrap. */
#define PART_MAX_COUNT ((uint64_t)1 << 56)

int part_check_contents(const struct part_file *pf, const char *path, struct err *e)
{
    const struct part_header *h = &pf->h;
    const struct render_stats *st = &h->st;
    uint64_t rows = (uint64_t)part_rows((int)h->height, (int)h->part, (int)h->parts);
    if (h->processes < 1 || h->processes > PROCS_MAX_PROCESSES)
        return err_set(e, path, 0, 0, "damaged part file: %u processes", h->processes);
    if (st->pixels != rows * h->width)
        return err_set(e, path, 0, 0, "damaged part file: counts %llu pixels but holds %llu",
                       (unsigned long long)st->pixels, (unsigned long long)(rows * h->width));
    if (st->samples >= PART_MAX_COUNT || st->rays >= PART_MAX_COUNT || st->light_sets >= PART_MAX_COUNT ||
        st->pixel_points >= PART_MAX_COUNT || st->light_points >= PART_MAX_COUNT ||
        st->padded_points >= PART_MAX_COUNT || st->padded_sets >= PART_MAX_COUNT ||
        st->shadow_rays > st->rays || st->nonfinite > st->samples ||
        (st->pixels > 0 && st->spp_min > st->spp_max) || st->samples < st->pixels * (uint64_t)st->spp_min ||
        st->samples > st->pixels * (uint64_t)st->spp_max || st->rays < st->samples)
        return err_set(e, path, 0, 0,
                       "damaged part file: impossible counts (%llu samples, %u to %u per pixel, %llu rays)",
                       (unsigned long long)st->samples, st->spp_min, st->spp_max,
                       (unsigned long long)st->rays);
    if (!(h->wall_s >= 0 && h->wall_s < 1e12 && h->cpu_s >= 0 && h->cpu_s < 1e12 && st->sampler_s >= 0 &&
          st->sampler_s <= h->cpu_s) ||
        h->peak_rss_kb >= PART_MAX_COUNT)
        return err_set(e, path, 0, 0, "damaged part file: impossible times or memory");
    const uint8_t *p = pf->data + PART_HEADER;
    for (uint64_t i = 0; i < rows * h->width * 3; i++) {
        uint64_t v = get_le(&p, 4);
        if ((v & 0x7f800000u) == 0x7f800000u) /* all exponent bits: inf or NaN */
            return err_set(e, path, 0, 0, "damaged part file: a non-finite pixel in row %llu of the image",
                           (unsigned long long)(h->part + i / (h->width * 3) * h->parts));
    }
    return 0;
}

int part_read(const char *path, struct part_file *pf, struct err *e)
{
    memset(pf, 0, sizeof *pf);
    /* the header first: the file may be no longer than the rows it says it holds */
    uint8_t head[PART_HEADER];
    struct err ignored;
    size_t max = PART_HEADER + 4;
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK), whole = 0;
    if (fd >= 0) {
        whole = read(fd, head, sizeof head) == (ssize_t)sizeof head;
        close(fd);
    }
    /* a header of another version (or a damaged one) says so, not "file too large" */
    if (whole && memcmp(head, PART_MAGIC, 8) == 0 && decode_header(head, sizeof head, path, &pf->h, e) < 0)
        return -1;
    if (whole && decode_header(head, sizeof head, path, &pf->h, &ignored) == 0)
        max = part_bytes(&pf->h);
    if (fileio_read_all(path, max, &pf->data, &pf->len, e) < 0)
        return -1;
    if (decode_header(pf->data, pf->len, path, &pf->h, e) < 0)
        return -1;
    if (pf->len != part_bytes(&pf->h))
        return err_set(e, path, 0, 0, "damaged part file: %zu bytes, expected %zu", pf->len,
                       part_bytes(&pf->h));
    const uint8_t *p = pf->data + pf->len - 4;
    if (get_le(&p, 4) != (uint32_t)crc32(0L, pf->data, (uInt)(pf->len - 4)))
        return err_set(e, path, 0, 0, "damaged part file: checksum mismatch");
    return 0;
}

void part_file_free(struct part_file *pf)
{
    free(pf->data);
    pf->data = NULL;
}

void part_rows_into(const struct part_file *pf, float *rgb)
{
    const int w = (int)pf->h.width, h = (int)pf->h.height, parts = (int)pf->h.parts;
    const uint8_t *p = pf->data + PART_HEADER;
    for (int y = (int)pf->h.part; y < h; y += parts)
        for (size_t i = 0; i < (size_t)w * 3; i++) {
            uint32_t v = (uint32_t)get_le(&p, 4);
            memcpy(&rgb[(size_t)y * w * 3 + i], &v, sizeof v);
        }
}

int part_matches(const char *path, const struct job *j, int part, int parts)
{
    struct part_file pf;
    struct err e;
    int ok = part_read(path, &pf, &e) == 0 && pf.h.hash == part_hash(j) && (int)pf.h.part == part &&
             (int)pf.h.parts == parts && part_check_contents(&pf, path, &e) == 0;
    part_file_free(&pf);
    return ok;
}
