/* test_outdir: the names in a job's output folder, the folder made and checked, and its lock
   removing only the temporaries of the paths it is taken for. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "job/job.h"
#include "job/outdir.h"

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

static void touch(const char *path)
{
    FILE *f = fopen(path, "w");
    if (f)
        fclose(f);
}

static int stem_is(const char *path, const char *want)
{
    char out[128];
    outdir_stem(path, out, sizeof out);
    if (strcmp(out, want) == 0)
        return 1;
    fprintf(stderr, "stem of \"%s\": \"%s\", expected \"%s\"\n", path, out, want);
    return 0;
}

static void test_names(void)
{
    CHECK(stem_is("scenes/checker.yaml", "checker"));
    CHECK(stem_is("cornell-box.v2.yaml", "cornell-box.v2"));
    CHECK(stem_is("a/b.c/plain", "plain")); /* a dot in a folder's name is no extension */
    CHECK(stem_is(".yaml", ".yaml"));       /* a leading dot starts no extension */
    CHECK(stem_is("image.png", "image"));
    CHECK(!strcmp(outdir_root(NULL), OUTDIR_DEFAULT) && !strcmp(OUTDIR_DEFAULT, "out"));
    CHECK(!strcmp(outdir_root("x"), "x"));

    struct job j;
    job_defaults(&j, "jobs/demo.yaml");
    snprintf(j.output, sizeof j.output, "pic.v1.png");
    char dir[256], part[256];
    struct outdir_files f;
    outdir_files(&j, NULL, &f);
    CHECK(!strcmp(f.dir, "out/demo"));
    CHECK(f.n_images == 1 && !strcmp(f.image[0], "out/demo/pic.v1.png") && f.float_copy == -1);
    CHECK(!strcmp(f.sidecar, "out/demo/pic.v1.json"));
    /* output: [pic.v1.png, pic.v1.exr], and a compare combination's float copy */
    j.n_more = 1;
    snprintf(j.more_output[0], sizeof j.more_output[0], "pic.v1.exr");
    j.more_format[0] = IMG_EXR;
    j.float_copy = 1;
    outdir_files(&j, "o", &f);
    CHECK(f.n_images == 2 && !strcmp(f.image[1], "o/demo/pic.v1.exr") && f.format[1] == IMG_EXR);
    CHECK(f.float_copy == -1); /* an EXR is listed: no second float image */
    j.n_more = 0;
    outdir_files(&j, "o", &f);
    CHECK(f.n_images == 2 && f.float_copy == 1 && !strcmp(f.image[1], "o/demo/pic.v1.exr"));
    CHECK(!strcmp(f.sidecar, "o/demo/pic.v1.json"));
    j.float_copy = 0;
    outdir_dir("o", "cmp", dir, sizeof dir);
    CHECK(!strcmp(dir, "o/cmp"));
    outdir_part_path(&j, "o", 2, 3, part, sizeof part);
    CHECK(!strcmp(part, "o/demo/pic.v1.part-2-of-3"));

    int i = -1, n = -1;
    CHECK(outdir_part_name(&j, "pic.v1.part-2-of-3", &i, &n) && i == 2 && n == 3);
    CHECK(!outdir_part_name(&j, "pic.v1.part-2-of-3.tmp", &i, &n));
    CHECK(!outdir_part_name(&j, "pic.part-2-of-3", &i, &n));
    CHECK(!outdir_part_name(&j, "pic.v1.json", &i, &n));
}

static void test_folder(const char *root)
{
    char deep[512], file[600];
    struct err e;
    int made = -1;
    snprintf(deep, sizeof deep, "%s/a/b/c", root);
    CHECK(outdir_check(deep, &e) == 0); /* can be made: nothing made yet */
    CHECK(!exists(deep));
    CHECK(outdir_mkdirs(deep, &made, &e) == 0 && made == 1 && exists(deep));
    CHECK(outdir_mkdirs(deep, &made, &e) == 0 && made == 0); /* there already: not ours */
    snprintf(file, sizeof file, "%s/plain", root);
    touch(file);
    snprintf(deep, sizeof deep, "%s/plain/sub", root);
    CHECK(outdir_check(deep, &e) < 0 && strstr(e.msg, "a file is in the way"));
    CHECK(outdir_mkdirs(deep, NULL, &e) < 0 && strstr(e.msg, "cannot create directory"));
}

static void test_lock(const char *root)
{
    char img[512], dead[600], old[600], other[600], live[600];
    snprintf(img, sizeof img, "%s/a/img.png", root);
    snprintf(old, sizeof old, "%s/a/..img.png.tmp.St4g3d.tmp.Zx8Cv7",
             root); /* staged twice (before issue 29) */
    touch(old);

    snprintf(dead, sizeof dead, "%s/a/.img.png.tmp.AbC123", root);
    snprintf(other, sizeof other, "%s/a/.other.png.tmp.AbC123", root);
    snprintf(live, sizeof live, "%s/a/img.png", root);
    touch(dead);
    touch(other);
    touch(live);
    char dir[512];
    snprintf(dir, sizeof dir, "%s/a", root);
    const char *paths[] = {img, NULL};
    int lock = outdir_lock(dir, paths, NULL, 0);
    CHECK(lock >= 0);
    CHECK(!exists(dead)); /* a killed writer's temporary of img.png: removed under the lock */
    CHECK(!exists(old));
    CHECK(exists(other)); /* another file's: kept */
    CHECK(exists(live));  /* the output itself: kept */
    outdir_unlock(lock);
    outdir_unlock(-1); /* no lock: nothing to do */
    snprintf(dir, sizeof dir, "%s/missing", root);
    CHECK(outdir_lock(dir, paths, NULL, 0) == -1);
}

int main(void)
{
    char root[] = "/tmp/test_outdir.XXXXXX";
    if (!mkdtemp(root))
        return 1;
    test_names();
    test_folder(root);
    test_lock(root);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", root);
    CHECK(system(cmd) == 0);
    return check_report("test_outdir");
}
