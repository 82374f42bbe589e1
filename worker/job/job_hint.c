/* job_hint: the nearest file name in a folder, for a scene path's "did you mean". */
#include "job_hint.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenefile/yamlx.h"

enum { HINT_NAME_MAX = 256 };

int job_hint_nearest(const char *dir, const char *name, int stems, char *out, size_t n)
{
    out[0] = 0;
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    char(*names)[HINT_NAME_MAX] = malloc(JOB_HINT_MAX_ENTRIES * sizeof *names);
    const char **list = malloc(JOB_HINT_MAX_ENTRIES * sizeof *list);
    int count = 0;
    struct dirent *de;
    for (int seen = 0; names && list && seen < JOB_HINT_MAX_ENTRIES && (de = readdir(d)); seen++) {
        size_t len = strlen(de->d_name);
        if (de->d_name[0] == '.' || len >= HINT_NAME_MAX)
            continue;
        if (stems) {
            if (len <= 5 || strcmp(de->d_name + len - 5, ".yaml") != 0)
                continue;
            len -= 5;
        }
        memcpy(names[count], de->d_name, len);
        names[count][len] = 0;
        list[count] = names[count];
        count++;
    }
    closedir(d);
    const char *near = count ? ystr_nearest(name, list, count) : NULL;
    if (near)
        snprintf(out, n, "%s", near);
    free(names);
    free(list);
    return near != NULL;
}
