/* compare_keys: the job keys a compare job accepts where (top level, variant, sweep, reference),
   a key applied by name, and the short forms of keys in image names and labels. */
#include "compare_keys.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

int compare_keys_apply(struct job *j, struct ydoc *d, const char *key, yaml_node_t *v, struct err *e)
{
    char text[COMPARE_LABEL_MAX];
    snprintf(text, sizeof text, "%s", key);
    yaml_node_t k;
    memset(&k, 0, sizeof k);
    k.type = YAML_SCALAR_NODE;
    k.data.scalar.value = (yaml_char_t *)text;
    k.data.scalar.length = strlen(text);
    return job_apply(j, d, &k, v, e);
}

const char *compare_keys_forbidden(const char *key, const char *where)
{
    int top = !strcmp(where, "top"), ref = !strcmp(where, "reference");
    if (!strcmp(key, "output") || !strcmp(key, "format"))
        return "a compare job names its images itself (<scene>-<variant>-t<threshold>-s<seed>.png)";
    if (top)
        return NULL;
    if (!strcmp(key, "scene"))
        return "a compare job lists its scenes once, under scenes:";
    if (!strcmp(key, "width") || !strcmp(key, "height"))
        return "the size is set once at the top level (every image is scored against one reference)";
    if (!strcmp(key, "name"))
        return "the job's name is set once at the top level";
    if (!strcmp(key, "reference"))
        return "the reference is set once at the top level";
    if (!strcmp(key, "seed") && !ref)
        return "list the seeds once, under seeds:";
    return NULL;
}

int compare_keys_check(struct ydoc *d, yaml_node_t *n, const char *where, const char *extra, struct err *e)
{
    const char *keys[JOB_KEYS_MAX + 2];
    int nk = job_key_list(keys, JOB_KEYS_MAX + 1);
    if (extra)
        keys[nk++] = extra;
    keys[nk] = NULL;
    if (ymap_check(d, n, keys, where, e) < 0)
        return -1;
    yaml_node_t *k, *v;
    for (int i = 0; ymap_pair(d, n, i, &k, &v); i++) {
        const char *why = compare_keys_forbidden(yscalar(k), where);
        if (why)
            return ydoc_fail(d, k, e, "%s: not allowed in a %s: %s", yscalar(k), where, why);
    }
    return 0;
}

/* Short forms of keys in labels and file names. */
static const char *short_key(const char *key)
{
    static const char *const map[][2] = {{"threshold", "t"},         {"light_threshold", "lt"},
                                         {"poisson_pool", "pool"},   {"max_depth", "depth"},
                                         {"processes", "p"},         {"sampler", ""},
                                         {"light_sampler", "light"}, {"russian_roulette", "roulette"}};
    for (size_t i = 0; i < sizeof map / sizeof map[0]; i++)
        if (!strcmp(map[i][0], key))
            return map[i][1];
    return key;
}

void compare_keys_append(char *buf, size_t n, const char *key, const char *val)
{
    size_t len = strlen(buf);
    snprintf(buf + len, n - len, "%s%s%s", len ? "-" : "", short_key(key), val);
    for (char *p = buf + len; *p; p++)
        if (!isalnum((unsigned char)*p) && !strchr(".-_", *p))
            *p = '_';
}
