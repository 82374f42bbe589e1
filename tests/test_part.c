/* test_part: part files round-trip, are matched to their inputs, and merge to the whole image. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <unistd.h>
#include <zlib.h>

#include "check.h"
#include "base/fileio.h"
#include "image/imgio.h"
#include "farm/merge.h"
#include "job/part.h"
#include "job/outdir.h"
#include "job/run_out.h"

enum { W = 7, H = 11 };

/* A framebuffer whose every value is distinct and exactly representable. */
static void fill(float *rgb)
{
    for (int i = 0; i < W * H * 3; i++)
        rgb[i] = (float)(i % 97) / 96.0f;
}

/* Stats a render of part `part` of `parts` of a w x h image could have: its pixels, 5 + part
   samples each (within spp 3 + part .. 9 + part), more rays than samples. */
static void result(struct procs_result *fr, int w, int h, int part, int parts)
{
    memset(fr, 0, sizeof *fr);
    render_stats_init(&fr->total);
    fr->total.pixels = (uint64_t)w * ((h - part + parts - 1) / parts);
    fr->total.samples = fr->total.pixels * (uint64_t)(5 + part);
    fr->total.rays = 100000000;
    fr->total.spp_min = 3 + part;
    fr->total.spp_max = 9 + part;
    fr->total.shadow_rays = 1000 + (uint64_t)part; /* the work counts: each part's own */
    fr->total.pixel_points = fr->total.samples;
    fr->total.light_points = 7 * (uint64_t)(part + 1);
    fr->total.padded_points = 100 + (uint64_t)part;
    fr->total.padded_sets = 10 * (uint64_t)(part + 1);
    fr->processes = 1;
    fr->wall_s = 0.5;
    fr->cpu_s = 0.25;
    fr->peak_rss_kb = 100 * (part + 1);
}

/* Rewrite n bytes at off of the part file at path and make its checksum again (a forgery). */
static void forge(const char *path, size_t off, const void *bytes, size_t n)
{
    uint8_t *data;
    size_t len;
    struct err e;
    CHECK(fileio_read_all(path, 1 << 20, &data, &len, &e) == 0);
    memcpy(data + off, bytes, n);
    uLong crc = crc32(0L, data, (uInt)(len - 4));
    for (int i = 0; i < 4; i++)
        data[len - 4 + i] = (uint8_t)(crc >> (8 * i));
    CHECK(fileio_write_atomic(path, data, len, &e) == 0);
    free(data);
}

/* Issue 27: part files forged whole (checksum made again) are refused: a size the job does not
   render (its height from the camera's aspect), another version (said so), non-finite rows,
   counters that would wrap, spp min over max. */
static void test_forged(const char *dir, const struct job *j0, const float *rgb0)
{
    struct job j = *j0;
    struct run_opts o = {.out_dir = dir};
    struct run_result rr;
    struct procs_result fr;
    struct err e;
    char path[2048], sub[2100];
    snprintf(j.name, sizeof j.name, "forged");
    snprintf(sub, sizeof sub, "%s/forged", dir);
    CHECK(outdir_mkdirs(sub, NULL, &e) == 0);
    outdir_part_path(&j, dir, 0, 1, path, sizeof path);
    /* no height: the camera's aspect gives it; a part 1 row high is not this job's */
    j.spec.height = 0;
    snprintf(j.scene_path, sizeof j.scene_path, "scenes/checker.yaml");
    result(&fr, W, 1, 0, 1);
    CHECK(part_write(path, &j, &(struct part_frame){W, 1, rgb0}, 0, 1, &fr, &e) == 0);
    CHECK(merge_parts(&j, &o, &rr, &e) == 2 && strstr(e.msg, "is 7x1 but the job renders 7x") != NULL);
    j.spec.height = H;
    result(&fr, W, H, 0, 1);
    CHECK(part_write(path, &j, &(struct part_frame){W, H, rgb0}, 0, 1, &fr, &e) == 0);
    CHECK(merge_parts(&j, &o, &rr, &e) == 0);
    /* another version says so (it said "file too large") */
    const uint32_t v1 = 1; /* format 1: before the work counts of issue 35 */
    forge(path, 8, &v1, 4);
    CHECK(merge_parts(&j, &o, &rr, &e) == 2 &&
          strstr(e.msg, "another worker version (part format 1") != NULL);
    /* wrapped counters: 2^64 - 2 samples; spp min over max */
    CHECK(part_write(path, &j, &(struct part_frame){W, H, rgb0}, 0, 1, &fr, &e) == 0);
    const uint64_t wrap = UINT64_MAX - 1;
    forge(path, 48, &wrap, 8);
    CHECK(merge_parts(&j, &o, &rr, &e) == 2 && strstr(e.msg, "impossible counts") != NULL);
    CHECK(part_write(path, &j, &(struct part_frame){W, H, rgb0}, 0, 1, &fr, &e) == 0);
    const uint32_t spp[2] = {9, 3};
    forge(path, 80, spp, 8);
    CHECK(merge_parts(&j, &o, &rr, &e) == 2 && strstr(e.msg, "impossible counts") != NULL);
    /* a NaN pixel in row 4 */
    static float nan_rows[W * H * 3];
    memcpy(nan_rows, rgb0, sizeof nan_rows);
    nan_rows[4 * W * 3 + 5] = NAN;
    CHECK(part_write(path, &j, &(struct part_frame){W, H, nan_rows}, 0, 1, &fr, &e) == 0);
    CHECK(merge_parts(&j, &o, &rr, &e) == 2 && strstr(e.msg, "non-finite pixel in row 4") != NULL);
    CHECK(part_matches(path, &j, 0, 1) == 0);
}

int main(void)
{
    char dir[] = "/tmp/test_part.XXXXXX", path[2048];
    CHECK(mkdtemp(dir) != NULL);
    struct job j;
    job_defaults(&j, "merge.yaml");
    snprintf(j.output, sizeof j.output, "merge.png");
    j.hash = 0x1234;
    j.spec.width = W; /* the size the job renders: merge checks the parts against it */
    j.spec.height = H;
    struct run_opts o = {.out_dir = dir};
    struct run_result rr;
    struct err e;
    static float rgb[W * H * 3];
    fill(rgb);

    /* the path names the split; the hash covers the inputs */
    outdir_part_path(&j, dir, 2, 3, path, sizeof path);
    CHECK(strstr(path, "/merge/merge.part-2-of-3") != NULL);
    struct job other = j;
    other.hash = 0x1235;
    CHECK(part_hash(&j) != part_hash(&other));

    /* no parts: refused */
    CHECK(merge_parts(&j, &o, &rr, &e) == 2);
    CHECK(strstr(e.msg, "no part files") != NULL);

    /* write 3 parts, with one missing first */
    char sub[2100];
    snprintf(sub, sizeof sub, "%s/merge", dir);
    CHECK(outdir_mkdirs(sub, NULL, &e) == 0);
    struct procs_result fr;
    for (int p = 0; p < 3; p += 2) {
        result(&fr, W, H, p, 3);
        outdir_part_path(&j, dir, p, 3, path, sizeof path);
        CHECK(part_write(path, &j, &(struct part_frame){W, H, rgb}, p, 3, &fr, &e) == 0);
        CHECK(part_matches(path, &j, p, 3) == 1);
        CHECK(part_matches(path, &other, p, 3) == 0);
        CHECK(part_matches(path, &j, (p + 1) % 3, 3) == 0);
    }
    CHECK(merge_parts(&j, &o, &rr, &e) == 2);
    CHECK(strstr(e.msg, "missing part 1 of 3") != NULL);
    result(&fr, W, H, 1, 3);
    outdir_part_path(&j, dir, 1, 3, path, sizeof path);
    CHECK(part_write(path, &j, &(struct part_frame){W, H, rgb}, 1, 3, &fr, &e) == 0);

    /* a part's file holds exactly its rows: header, ceil((11 - 1) / 3) = 4 rows, CRC */
    uint8_t *data;
    size_t len;
    CHECK(fileio_read_all(path, 1 << 20, &data, &len, &e) == 0);
    CHECK(len == 160 + 4 * W * 12 + 4);
    CHECK(memcmp(data, "WPART\r\n\x1a", 8) == 0);
    free(data);

    /* the merge gives the whole image and sums the stats */
    CHECK(merge_parts(&j, &o, &rr, &e) == 0);
    CHECK(rr.width == W && rr.height == H);
    CHECK(rr.procs.processes == 3);
    CHECK(rr.procs.total.pixels == W * H);
    CHECK(rr.procs.total.samples == 4 * W * 5 + 4 * W * 6 + 3 * W * 7);
    CHECK(rr.procs.total.spp_min == 3 && rr.procs.total.spp_max == 11);
    CHECK_NEAR(rr.procs.cpu_s, 0.75, 1e-12);
    CHECK(rr.procs.peak_rss_kb == 300);
    CHECK(rr.procs.proc[1].st.samples == 4 * W * 6);
    /* issue 35: the work counts come through the part files and are summed */
    CHECK(rr.procs.total.shadow_rays == 3003 && rr.procs.total.light_points == 42);
    CHECK(rr.procs.total.pixel_points == rr.procs.total.samples);
    CHECK(rr.procs.total.padded_points == 303 && rr.procs.total.padded_sets == 60);
    struct rgb8 got, want;
    CHECK(imgio_read(rr.out.image[0], &got, &e) == 0);
    CHECK(image_alloc(&want, W, H, &e) == 0);
    image_float_to_rgb8(rgb, W, H, want.px);
    CHECK(got.w == W && got.h == H && memcmp(got.px, want.px, (size_t)W * H * 3) == 0);
    image_free(&got);
    image_free(&want);
    CHECK(fileio_read_all(rr.out.sidecar, 1 << 20, &data, &len, &e) == 0);
    CHECK(strstr((char *)data, "\"parts\": 3") != NULL);
    CHECK(strstr((char *)data, "\"job_hash\": \"0000000000001234\"") != NULL);
    free(data);

    /* a part from other inputs is refused, naming the file */
    outdir_part_path(&j, dir, 0, 3, path, sizeof path);
    result(&fr, W, H, 0, 3);
    CHECK(part_write(path, &other, &(struct part_frame){W, H, rgb}, 0, 3, &fr, &e) == 0);
    CHECK(merge_parts(&j, &o, &rr, &e) == 2);
    CHECK(strstr(e.file, "merge.part-0-of-3") != NULL && strstr(e.msg, "other inputs") != NULL);
    CHECK(part_write(path, &j, &(struct part_frame){W, H, rgb}, 0, 3, &fr, &e) == 0);

    /* a flipped byte in the rows fails the checksum */
    outdir_part_path(&j, dir, 2, 3, path, sizeof path);
    CHECK(fileio_read_all(path, 1 << 20, &data, &len, &e) == 0);
    data[130] ^= 1;
    CHECK(fileio_write_atomic(path, data, len, &e) == 0);
    free(data);
    CHECK(merge_parts(&j, &o, &rr, &e) == 2);
    CHECK(strstr(e.msg, "checksum") != NULL);
    CHECK(part_matches(path, &j, 2, 3) == 0); /* a damaged part is not current: resume renders it */

    /* parts of an image over 1e8 pixels (a render allows sides up to 32768) are parts like any
       other: a part of a 10240x10240 image, split 256 ways (40 rows), matches its job */
    {
        enum { BW = 10240, BH = 10240, BPARTS = 256 };
        float *big = calloc((size_t)BW * BH * 3, sizeof *big); /* only the part's rows are touched */
        CHECK(big != NULL);
        if (big) {
            struct job bj = j;
            snprintf(bj.name, sizeof bj.name, "big");
            snprintf(sub, sizeof sub, "%s/big", dir);
            CHECK(outdir_mkdirs(sub, NULL, &e) == 0);
            result(&fr, BW, BH, 5, BPARTS);
            outdir_part_path(&bj, dir, 5, BPARTS, path, sizeof path);
            CHECK(part_write(path, &bj, &(struct part_frame){BW, BH, big}, 5, BPARTS, &fr, &e) == 0);
            CHECK(part_matches(path, &bj, 5, BPARTS) == 1);
            free(big);
        }
    }

    test_forged(dir, &j, rgb);
    char cmd[2200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    return check_report("test_part");
}
