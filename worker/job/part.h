/* part: one share of an image (rows with row % N == I) in a small binary file, written by a
   `--part I/N` render and read back by the merge (farm/merge.h). */
#ifndef PART_H
#define PART_H

#include <stddef.h>
#include <stdint.h>

#include "procs.h"
#include "job.h"

#define PART_VERSION 2
#define PART_MAX PROCS_MAX_PROCESSES /* most parts one image may be split into */

/* What a part must have been rendered from to merge with j's other parts: j->hash (job file and
   scene bytes), the part format and the worker's version. */
uint64_t part_hash(const struct job *j);

/* A whole w x h framebuffer of rgb floats, which a part is cut from. */
struct part_frame {
    int w, h;
    const float *rgb;
};

/* Write part I of N of the render fb (only the part's rows are stored) with fr's stats,
   atomically. Layout, little-endian: "WPART\r\n\x1a", u32 version,
   width, height, part, parts, processes, u64 hash, u64 pixels, samples, rays, light sets,
   non-finite, u32 spp min, max, f64 sampler_s, wall_s, cpu_s, u64 peak RSS (kB), u64 shadow rays,
   pixel points, light points, padded points, padded sets (format 2); then the part's rows in
   order, width * 3 f32 each; then a u32 CRC-32 of everything before. 0 or -1 with e filled. */
int part_write(const char *path, const struct job *j, const struct part_frame *fb, int part, int parts,
               const struct procs_result *fr, struct err *e);

/* 1 when the part file at path is whole (length, checksum) and was rendered as part I of N from j's inputs.
 */
int part_matches(const char *path, const struct job *j, int part, int parts);

/* A part file's header: its split, size and the stats of the render that made it. */
struct part_header {
    uint32_t version, width, height, part, parts, processes;
    uint64_t hash;
    struct render_stats st;
    double wall_s, cpu_s;
    uint64_t peak_rss_kb;
};

/* A part file read whole and checked: its header, and its bytes (owned) holding the rows. */
struct part_file {
    struct part_header h;
    uint8_t *data;
    size_t len;
};

/* Read the part file at path into pf, checking its magic, version, split, length and checksum. 0
   or -1 with e filled (file = path); part_file_free(pf) either way. */
int part_read(const char *path, struct part_file *pf, struct err *e);
void part_file_free(struct part_file *pf);

/* Whether pf (read by part_read) holds what a render can have written: counts that agree and
   cannot wrap when PART_MAX parts are summed, sane times, finite pixels. 0 or -1 with e filled. */
int part_check_contents(const struct part_file *pf, const char *path, struct err *e);

/* Copy pf's rows (row % parts == part) into rgb, a framebuffer of pf's width x height. */
void part_rows_into(const struct part_file *pf, float *rgb);

#endif
