/* test_sidecar: sidecars written by sidecar_json read back by sidecar_read (numbers, hash, names
   with escapes and other encodings), sidecar_matches, and malformed files refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/fileio.h"
#include "base/json.h"
#include "check.h"
#include "job/sidecar.h"

static char dir[] = "/tmp/test_sidecar.XXXXXX";
static char path[256];

static struct procs_result *result(void)
{
    static struct procs_result r;
    memset(&r, 0, sizeof r);
    r.processes = 2;
    r.total = (struct render_stats){.pixels = 12,
                                    .samples = 300,
                                    .rays = 900,
                                    .spp_min = 20,
                                    .spp_max = 30,
                                    .sampler_s = 0.25,
                                    .shadow_rays = 200,
                                    .light_sets = 4,
                                    .pixel_points = 300,
                                    .light_points = ((uint64_t)1 << 60) +
                                                    1, /* past a double's 53 bits: read as a whole number */
                                    .padded_points = 55,
                                    .padded_sets = 9};
    r.wall_s = 1.5;
    r.cpu_s = 2.5;
    r.proc[0] = (struct procs_proc){.st = {.pixels = 6, .samples = 150}, .wall_s = 0.5, .cpu_s = 1.25};
    r.proc[1] = (struct procs_proc){.st = {.pixels = 6, .samples = 150}, .wall_s = 1.5, .cpu_s = 1.5};
    r.peak_rss_kb = 1234;
    return &r;
}

/* Write j's sidecar (with error figures m, may be NULL) to path; 0 or -1. */
static int write_sidecar(const struct job *j, const struct metrics *m)
{
    struct sidecar sc = {j, 4, 3, result(), m, IMG_LINEAR, j->output, 0};
    char *text = sidecar_json(&sc);
    struct err e;
    int rc = text && fileio_write_atomic(path, text, strlen(text), &e) == 0 ? 0 : -1;
    free(text);
    return rc;
}

static int write_text(const char *text)
{
    struct err e;
    return fileio_write_atomic(path, text, strlen(text), &e);
}

static void test_round_trip(void)
{
    struct job j;
    job_defaults(&j, "jobs/demo.yaml");
    snprintf(j.output, sizeof j.output, "demo.png");
    snprintf(j.reference, sizeof j.reference, "refs/demo.exr");
    j.hash = 0x0123456789abcdefULL;
    struct metrics m = {0.5, sqrt(0.5), 0.125, 0.0625, INFINITY}; /* psnr of equal images: written null */
    CHECK(write_sidecar(&j, &m) == 0);
    struct sidecar_info in;
    struct err e;
    CHECK(sidecar_read(path, &in, &e) == 0);
    CHECK(!strcmp(in.job, "demo") && !strcmp(in.job_file, "jobs/demo.yaml") && !strcmp(in.image, "demo.png"));
    CHECK(in.has_hash && in.job_hash == 0x0123456789abcdefULL);
    CHECK(in.spec.width == 4 && in.spec.height == 3 && in.processes == 2 && in.parts == 0);
    CHECK(in.samples_total == 300 && in.spp_min == 20 && in.spp_max == 30);
    CHECK(in.spp_mean == 25);
    CHECK(in.wall_s == 1.5 && in.cpu_s == 2.5 && in.sampler_s == 0.25); /* the job's, not per_process */
    CHECK_NEAR(in.sampling_share, 0.1, 1e-12);                          /* 0.25 s of the 2.5 s of CPU */
    CHECK(in.has_error && in.mse == 0.5 && in.relmse == 0.125 && in.relmse_robust == 0.0625 &&
          isnan(in.psnr));
    CHECK(!strcmp(in.error_domain, image_domain_name(IMG_LINEAR)));
    CHECK(!strcmp(in.reference, "refs/demo.exr")); /* worker verdict finds the reference by it */
    CHECK_NEAR(in.rmse, sqrt(0.5), 1e-9);          /* written with 10 digits */
    /* issue 35: the work counts, path segments being the rays that are not shadow rays */
    CHECK(in.has_work && in.work.camera_samples == 300 && in.work.path_segments == 700 &&
          in.work.shadow_rays == 200);
    CHECK(in.work.pixel_points == 300 && in.work.light_points == ((uint64_t)1 << 60) + 1 &&
          in.work.padded_points == 55);
    CHECK(in.work.pixel_sets == 12 && in.work.light_sets == 4 && in.work.padded_sets == 9);
    CHECK(sidecar_matches(path, 0x0123456789abcdefULL) == 1);
    CHECK(sidecar_matches(path, 0x0123456789abcdeeULL) == 0);
    j.hash = 0;
    CHECK(write_sidecar(&j, NULL) == 0);
    CHECK(sidecar_read(path, &in, &e) == 0 && !in.has_error && in.job_hash == 0);
    CHECK(sidecar_matches("/nonexistent/x.json", 0) == 0);
}

/* A job file named `name` reads back from its sidecar as `want`. */
static int name_reads_back(const char *name, const char *want)
{
    struct job j;
    job_defaults(&j, name);
    snprintf(j.output, sizeof j.output, "x.png");
    struct sidecar_info in;
    struct err e;
    if (write_sidecar(&j, NULL) < 0 || sidecar_read(path, &in, &e) < 0) {
        fprintf(stderr, "cannot read back the sidecar of \"%s\": %s\n", name, e.msg);
        return 0;
    }
    return strcmp(in.job_file, want) == 0;
}

static void test_names(void)
{
    CHECK(name_reads_back("q\"uote.yaml", "q\"uote.yaml"));
    CHECK(name_reads_back("back\\slash\\.yaml", "back\\slash\\.yaml"));
    CHECK(name_reads_back("a\tb.yaml", "a\tb.yaml"));
    CHECK(name_reads_back("new\nline\r.yaml", "new\nline\r.yaml"));
    CHECK(name_reads_back("dir/caf\xc3\xa9 \xe2\x80\xa8 \xe2\x80\xa9 \xf0\x9f\x98\x80.yaml",
                          "dir/caf\xc3\xa9 \xe2\x80\xa8 \xe2\x80\xa9 \xf0\x9f\x98\x80.yaml"));
    /* YAML refuses these raw or folds them (NEL): the writer escapes them */
    CHECK(name_reads_back("del\x7f nel\xc2\x85 c1\xc2\x80 \xef\xbf\xbe.yaml",
                          "del\x7f nel\xc2\x85 c1\xc2\x80 \xef\xbf\xbe.yaml"));
    /* Latin-1 is not UTF-8: each such byte is recorded as U+FFFD, as json_string_read_back says */
    char back[64];
    CHECK(json_string_read_back("caf\xe9.yaml", back, sizeof back) == 0 &&
          !strcmp(back, "caf\xef\xbf\xbd.yaml"));
    CHECK(name_reads_back("caf\xe9.yaml", back));
    CHECK(json_string_read_back("caf\xe9.yaml", back, 8) == -1); /* does not fit */
}

static int refused(const char *text, const char *why)
{
    struct sidecar_info in;
    struct err e;
    if (write_text(text) < 0)
        return 0;
    if (sidecar_read(path, &in, &e) == 0) {
        fprintf(stderr, "read without error: %s\n", text);
        return 0;
    }
    if (strstr(e.msg, why) && !strcmp(e.file, path))
        return 1;
    fprintf(stderr, "%s: %s (expected \"%s\")\n", text, e.msg, why);
    return 0;
}

static void test_malformed(void)
{
    CHECK(refused("{\"job\": \"x\", ", "syntax error"));
    CHECK(refused("[1, 2]", "one JSON object"));
    CHECK(refused("", "empty"));
    CHECK(refused("{\"job\": [1]}", "job: expected a value"));
    CHECK(refused("{\"width\": \"wide\"}", "width: expected a whole number"));
    CHECK(refused("{\"width\": -4}", "width: expected a whole number"));
    CHECK(refused("{\"sampler\": \"jiter\"}", "sampler: expected uniform, jitter,"));
    CHECK(refused("{\"threshold\": 0}", "threshold: expected a number in (0, 100]"));
    CHECK(refused("{\"integrator\": \"NEE\"}", "integrator: expected mixture or nee"));
    CHECK(refused("{\"time\": {\"wall_s\": \"slow\"}}", "wall_s: expected a number"));
    CHECK(refused("{\"time\": 5}", "time: expected an object"));
    CHECK(refused("{\"job\": \"a\\u0000b\"}", "NUL"));
    char long_name[JOB_NAME_MAX + 32];
    snprintf(long_name, sizeof long_name, "{\"job\": \"%0*d\"}", JOB_NAME_MAX + 8, 0);
    CHECK(refused(long_name, "job: longer than"));
    /* a file over the bound is not read */
    size_t big = SIDECAR_MAX_BYTES + 16;
    char *text = malloc(big + 1);
    if (text) {
        memset(text, ' ', big);
        memcpy(text, "{\"job\": \"x\"}", 12);
        text[big] = 0;
        CHECK(refused(text, ""));
        free(text);
    }
    /* absent keys stay 0; a hash that is not 16 hex digits is none */
    struct sidecar_info in;
    struct err e;
    CHECK(write_text("{\"job_hash\": \"xyz\", \"job\": \"j\"}") == 0);
    CHECK(sidecar_read(path, &in, &e) == 0 && !in.has_hash && !strcmp(in.job, "j") && in.wall_s == 0);
    CHECK(sidecar_matches(path, 0) == 0);
}

int main(void)
{
    if (!mkdtemp(dir))
        return 1;
    snprintf(path, sizeof path, "%s/s.json", dir);
    test_round_trip();
    test_names();
    test_malformed();
    unlink(path);
    rmdir(dir);
    return check_report("test_sidecar");
}
