/* test_part: part files round-trip, are matched to their inputs, and merge to the whole image. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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

static void result(struct procs_result *fr, int part)
{
    memset(fr, 0, sizeof *fr);
    render_stats_init(&fr->total);
    fr->total.pixels = 10 + part;
    fr->total.samples = 100 + part;
    fr->total.rays = 1000;
    fr->total.spp_min = 3 + part;
    fr->total.spp_max = 9 + part;
    fr->processes = 1;
    fr->wall_s = 0.5;
    fr->cpu_s = 0.25;
    fr->peak_rss_kb = 100 * (part + 1);
}

int main(void)
{
    char dir[] = "/tmp/test_part.XXXXXX", path[2048];
    CHECK(mkdtemp(dir) != NULL);
    struct job j;
    job_defaults(&j, "merge.yaml");
    snprintf(j.output, sizeof j.output, "merge.png");
    j.hash = 0x1234;
    j.width = W; /* the size the job renders: merge checks the parts against it */
    j.height = H;
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
        result(&fr, p);
        outdir_part_path(&j, dir, p, 3, path, sizeof path);
        CHECK(part_write(path, &j, W, H, p, 3, rgb, &fr, &e) == 0);
        CHECK(part_matches(path, &j, p, 3) == 1);
        CHECK(part_matches(path, &other, p, 3) == 0);
        CHECK(part_matches(path, &j, (p + 1) % 3, 3) == 0);
    }
    CHECK(merge_parts(&j, &o, &rr, &e) == 2);
    CHECK(strstr(e.msg, "missing part 1 of 3") != NULL);
    result(&fr, 1);
    outdir_part_path(&j, dir, 1, 3, path, sizeof path);
    CHECK(part_write(path, &j, W, H, 1, 3, rgb, &fr, &e) == 0);

    /* a part's file holds exactly its rows: header, ceil((11 - 1) / 3) = 4 rows, CRC */
    uint8_t *data;
    size_t len;
    CHECK(fileio_read_all(path, 1 << 20, &data, &len, &e) == 0);
    CHECK(len == 120 + 4 * W * 12 + 4);
    CHECK(memcmp(data, "WPART\r\n\x1a", 8) == 0);
    free(data);

    /* the merge gives the whole image and sums the stats */
    CHECK(merge_parts(&j, &o, &rr, &e) == 0);
    CHECK(rr.width == W && rr.height == H);
    CHECK(rr.procs.processes == 3);
    CHECK(rr.procs.total.pixels == 10 + 11 + 12);
    CHECK(rr.procs.total.samples == 100 + 101 + 102);
    CHECK(rr.procs.total.spp_min == 3 && rr.procs.total.spp_max == 11);
    CHECK_NEAR(rr.procs.cpu_s, 0.75, 1e-12);
    CHECK(rr.procs.peak_rss_kb == 300);
    CHECK(rr.procs.proc[1].st.samples == 101);
    struct rgb8 got, want;
    CHECK(imgio_read(rr.image_path, &got, &e) == 0);
    CHECK(image_alloc(&want, W, H, &e) == 0);
    image_float_to_rgb8(rgb, W, H, want.px);
    CHECK(got.w == W && got.h == H && memcmp(got.px, want.px, (size_t)W * H * 3) == 0);
    image_free(&got);
    image_free(&want);
    CHECK(fileio_read_all(rr.sidecar_path, 1 << 20, &data, &len, &e) == 0);
    CHECK(strstr((char *)data, "\"parts\": 3") != NULL);
    CHECK(strstr((char *)data, "\"job_hash\": \"0000000000001234\"") != NULL);
    free(data);

    /* a part from other inputs is refused, naming the file */
    outdir_part_path(&j, dir, 0, 3, path, sizeof path);
    result(&fr, 0);
    CHECK(part_write(path, &other, W, H, 0, 3, rgb, &fr, &e) == 0);
    CHECK(merge_parts(&j, &o, &rr, &e) == 2);
    CHECK(strstr(e.file, "merge.part-0-of-3") != NULL && strstr(e.msg, "other inputs") != NULL);
    CHECK(part_write(path, &j, W, H, 0, 3, rgb, &fr, &e) == 0);

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
            result(&fr, 5);
            outdir_part_path(&bj, dir, 5, BPARTS, path, sizeof path);
            CHECK(part_write(path, &bj, BW, BH, 5, BPARTS, big, &fr, &e) == 0);
            CHECK(part_matches(path, &bj, 5, BPARTS) == 1);
            free(big);
        }
    }

    char cmd[2200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    return check_report("test_part");
}
