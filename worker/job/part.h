/* part: one share of an image (rows with row % N == I) in a small binary file, and the merge. */
#ifndef PART_H
#define PART_H

#include <stddef.h>
#include <stdint.h>

#include "procs.h"
#include "job.h"
#include "run.h"

#define PART_VERSION 1
#define PART_MAX PROCS_MAX_PROCESSES /* most parts one image may be split into */

/* What a part must have been rendered from to merge with j's other parts: j->hash (job file and
   scene bytes), the part format and the worker's version. */
uint64_t part_hash(const struct job *j);

/* Write part I of N of a w x h render (rgb: the whole framebuffer; only the part's rows are
   stored) with fr's stats, atomically. Layout, little-endian: "WPART\r\n\x1a", u32 version,
   width, height, part, parts, processes, u64 hash, u64 pixels, samples, rays, light sets,
   non-finite, u32 spp min, max, f64 sampler_s, wall_s, cpu_s, u64 peak RSS (kB); then the part's rows in
   order, width * 3 f32 each; then a u32 CRC-32 of everything before. 0 or -1 with e filled. */
int part_write(const char *path, const struct job *j, int w, int h, int part, int parts, const float *rgb,
               const struct procs_result *fr, struct err *e);

/* 1 when the part file at path is whole (length, checksum) and was rendered as part I of N from j's inputs.
 */
int part_matches(const char *path, const struct job *j, int part, int parts);

/* Merge every part of j found under o->out_dir into the image and a sidecar whose stats sum the
   parts' (one per_process entry per part). 0 on success; 2 when parts are missing, of different
   splits, damaged or rendered from other inputs (nothing written, e says which); 1 when writing
   failed. */
int part_merge(const struct job *j, const struct run_opts *o, struct run_result *rr, struct err *e);

#endif
