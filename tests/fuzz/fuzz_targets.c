/* fuzz_targets: the job parser, the scene parser, the PNG/PPM readers and `worker verdict`'s
   summary.csv reader on arbitrary bytes. */
#include "fuzz_targets.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "image/exr.h"
#include "image/image.h"
#include "image/pfm.h"
#include "job/job.h"
#include "job/jobfile.h"
#include "image/png.h"
#include "image/ppm.h"
#include "scenefile/scene_load.h"
#include "study/run/verdict_load.h"

/* The loaders read files: write the input to a private temporary file first. */
static int with_file(const uint8_t *data, size_t size, char *path, size_t n)
{
    const char *dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    snprintf(path, n, "%s/fuzz-%ld.yaml", dir, (long)getpid());
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    size_t w = fwrite(data, 1, size, f);
    fclose(f);
    return w == size ? 0 : -1;
}

int fuzz_job(const uint8_t *data, size_t size)
{
    char path[256];
    struct jobfile f;
    struct err e;
    if (with_file(data, size, path, sizeof path) == 0) {
        jobfile_open(&f, path, path, &e);
        jobfile_close(&f);
    }
    unlink(path);
    return 0;
}

int fuzz_scene(const uint8_t *data, size_t size)
{
    char path[256];
    struct scene_file sf;
    struct err e;
    if (with_file(data, size, path, sizeof path) == 0 && scene_load(path, &sf, &e) == 0)
        scene_file_free(&sf);
    unlink(path);
    return 0;
}

int fuzz_image(const uint8_t *data, size_t size)
{
    struct rgb8 img = {0};
    struct err e;
    if (png_decode(data, size, "fuzz", &img, &e) == 0)
        image_free(&img);
    struct rgb8 img2 = {0};
    if (ppm_decode(data, size, "fuzz", &img2, &e) == 0)
        image_free(&img2);
    struct rgbf f = {0};
    if (pfm_decode(data, size, "fuzz", &f, &e) == 0)
        image_f_free(&f);
    if (exr_image_decode(data, size, "fuzz", &f, &e) == 0)
        image_f_free(&f);
    return 0;
}

/* The bytes as DIR/summary.csv of a private folder, judged as `worker verdict DIR` does. */
int fuzz_summary(const uint8_t *data, size_t size)
{
    char dir[256], path[300], job[64];
    const char *base = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    snprintf(dir, sizeof dir, "%s/fuzz-summary-%ld", base, (long)getpid());
    snprintf(path, sizeof path, "%s/summary.csv", dir);
    mkdir(dir, 0700);
    FILE *f = fopen(path, "wb");
    if (f) {
        size_t w = fwrite(data, 1, size, f);
        fclose(f);
        struct verdict_study *s = NULL;
        struct err e;
        int n = 0;
        if (w == size && verdict_load_dir(dir, &s, &n, job, sizeof job, &e) == 0)
            for (int i = 0; i < n; i++)
                verdict_study_free(&s[i]);
        free(s);
    }
    unlink(path);
    rmdir(dir);
    return 0;
}
