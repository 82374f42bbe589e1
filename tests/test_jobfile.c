/* Tests for jobfile: one read and one parse of a job file, its kind, hash and scene. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/hash.h"
#include "check.h"
#include "job/jobfile.h"
#include "job_fixture.h"
#include "scenefile/scene_src.h"

static struct job_fixture fx;

/* The kind jobfile_open reads text as; -1 when it does not open (e filled). */
static int kind_of(const char *text, struct err *e)
{
    char path[128];
    struct jobfile f;
    job_fixture_put(&fx, "k.yaml", text, path, sizeof path);
    int kind = jobfile_open(&f, path, path, e) == 0 ? (int)f.kind : -1;
    jobfile_close(&f);
    unlink(path);
    return kind;
}

static void test_kinds(void)
{
    struct err e;
    char text[1200];
    snprintf(text, sizeof text, "scene: %s\n", fx.scene);
    CHECK(kind_of(text, &e) == JOBFILE_PLAIN);
    CHECK(kind_of("variants:\n  - { sampler: jitter }\n", &e) == JOBFILE_COMPARE);
    CHECK(kind_of("variants:\n", &e) == JOBFILE_COMPARE); /* null: still meant as one (its loader says) */
    CHECK(kind_of("name: s\nstudies: [a.yaml]\nvariants: []\n", &e) == JOBFILE_SUITE);
    CHECK(kind_of("variants: [\n", &e) == -1 && strstr(e.msg, "YAML syntax error") && e.line == 2);
    CHECK(kind_of("- a\n", &e) == -1 && strstr(e.msg, "expected a mapping")); /* a plain job's reader says */
    CHECK(kind_of("widht: 3\n", &e) == -1 && strstr(e.msg, "did you mean \"width\""));
}

/* jobfile_peek_kind: the kind alone, nothing checked; a file that does not read or parse is plain. */
static void test_peek_kind(void)
{
    char path[128];
    job_fixture_put(&fx, "s.yaml", "name: s\nstudies: [a.yaml]\n", path, sizeof path);
    CHECK(jobfile_peek_kind(path) == JOBFILE_SUITE);
    job_fixture_put(&fx, "s.yaml", "variants: [{ sampler: nonesuch }]\nwidht: 3\n", path, sizeof path);
    CHECK(jobfile_peek_kind(path) == JOBFILE_COMPARE); /* its keys are the loader's to judge */
    job_fixture_put(&fx, "s.yaml", "scene: missing.yaml\n", path, sizeof path);
    CHECK(jobfile_peek_kind(path) == JOBFILE_PLAIN); /* its scene is not read */
    job_fixture_put(&fx, "s.yaml", "variants: [\n", path, sizeof path);
    CHECK(jobfile_peek_kind(path) == JOBFILE_PLAIN);
    unlink(path);
    CHECK(jobfile_peek_kind(path) == JOBFILE_PLAIN);
}

/* The hash: the job file's bytes, then the scene's (the value run_job's resume and sidecars
   record: the same as before the file was read once). */
static void test_hash_and_scene(void)
{
    char path[128], text[1200];
    struct jobfile f;
    struct err e;
    CHECK(job_fixture_open(&fx, "h.yaml", "width: 8\n", path, sizeof path, &f, &e) == 0);
    snprintf(text, sizeof text, "scene: %s\nwidth: 8\n", fx.scene);
    CHECK(f.hash == hash_bytes(HASH_FNV_OFFSET, text, strlen(text)));
    uint64_t want = f.hash;
    struct scene_src src;
    CHECK(scene_src_read(fx.scene, &src, &want, &e) == 0);
    scene_src_free(&src);
    CHECK(f.job.hash == want && f.job.spec.width == 8);
    CHECK(f.scene.parsed && !strcmp(f.scene.doc.file, fx.scene)); /* parsed once, kept for the render */
    struct scene_file sf;
    CHECK(scene_load_src(&f.scene, &sf, &e) == 0 && sf.scene != NULL);
    scene_file_free(&sf);
    CHECK(scene_load_src(&f.scene, &sf, &e) == 0); /* again from the same parse: a retried render */
    scene_file_free(&sf);
    jobfile_close(&f);

    /* read from one place as if at another: messages name the other (a queue's claimed file) */
    CHECK(jobfile_open(&f, path, "queue/h.yaml", &e) == 0 && !strcmp(f.job.path, "queue/h.yaml"));
    jobfile_close(&f);
    unlink(path);
    CHECK(jobfile_open(&f, path, "queue/h.yaml", &e) < 0 && !strcmp(e.file, "queue/h.yaml"));
    jobfile_close(&f);

    /* a scene that does not parse: the job opens, the scene's error comes when it is loaded */
    char bad[128];
    job_fixture_put(&fx, "bad-scene.yaml", "camera: [\n", bad, sizeof bad);
    snprintf(text, sizeof text, "scene: %s\n", bad);
    job_fixture_put(&fx, "b.yaml", text, path, sizeof path);
    CHECK(jobfile_open(&f, path, path, &e) == 0 && !f.scene.parsed);
    CHECK(scene_load_src(&f.scene, &sf, &e) < 0 && strstr(e.msg, "YAML syntax error") &&
          !strcmp(e.file, bad));
    jobfile_close(&f);
    unlink(path);
    unlink(bad);
}

static void test_output_list(void)
{
    char path[128];
    struct jobfile f;
    struct err e;
    CHECK(job_fixture_open(&fx, "o.yaml", "output: [a.png, a.exr, a.PFM]\n", path, sizeof path, &f, &e) == 0);
    CHECK(!strcmp(f.job.output, "a.png") && f.job.format == IMG_PNG && f.job.n_more == 2);
    CHECK(!strcmp(f.job.more_output[0], "a.exr") && f.job.more_format[0] == IMG_EXR);
    CHECK(!strcmp(f.job.more_output[1], "a.PFM") && f.job.more_format[1] == IMG_PFM);
    jobfile_close(&f);
    unlink(path);
}

int main(void)
{
    if (job_fixture_init(&fx, "test_jobfile") < 0)
        return 1;
    test_kinds();
    test_peek_kind();
    test_hash_and_scene();
    test_output_list();
    rmdir(fx.dir);
    return check_report("test_jobfile");
}
