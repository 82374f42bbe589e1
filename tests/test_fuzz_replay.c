/* Replays every fuzz seed and every regression input (tests/fuzz/<target>/ and
   tests/fuzz/regress/<target>-*) through the fuzz targets: none may crash (ASan runs this too). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "base/fileio.h"
#include "fuzz/fuzz_targets.c"

typedef int (*target_fn)(const uint8_t *, size_t);

static int replay_dir(const char *dir, const char *prefix, target_fn fn)
{
    DIR *d = opendir(dir);
    int n = 0;
    if (!d)
        return 0;
    struct dirent *ent;
    while ((ent = readdir(d))) {
        if (ent->d_name[0] == '.' || (prefix && strncmp(ent->d_name, prefix, strlen(prefix))))
            continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, ent->d_name);
        uint8_t *data;
        size_t len;
        struct err e;
        if (fileio_read_all(path, 1 << 24, &data, &len, &e) < 0)
            continue;
        CHECK(fn(data, len) == 0);
        free(data);
        n++;
    }
    closedir(d);
    return n;
}

int main(void)
{
    const char *names[] = {"job", "scene", "image", "summary"};
    target_fn fns[] = {fuzz_job, fuzz_scene, fuzz_image, fuzz_summary};
    int total = 0;
    for (int i = 0; i < 4; i++) {
        char dir[64], prefix[64];
        snprintf(dir, sizeof dir, "tests/fuzz/%s", names[i]);
        snprintf(prefix, sizeof prefix, "%s-", names[i]);
        int seeds = replay_dir(dir, NULL, fns[i]);
        int regress = replay_dir("tests/fuzz/regress", prefix, fns[i]);
        CHECK(seeds > 0);
        printf("%s: %d seeds, %d regression inputs replayed\n", names[i], seeds, regress);
        total += seeds + regress;
    }
    /* The bad-input corpus is YAML too: every file through both parsers. */
    total += replay_dir("tests/bad", "job-", fuzz_job) + replay_dir("tests/bad", "scene-", fuzz_scene);
    printf("%d inputs replayed\n", total);
    return check_report("test_fuzz_replay");
}
