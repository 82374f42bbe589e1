/* scene_parse: the scene loader's shared checks: names looked up with a "did you mean", colours. */
#include "scene_parse.h"

#include <string.h>

#include "yget.h"

int scene_parse_find_name(const struct names *nm, const char *s)
{
    for (int i = 0; i < nm->n; i++)
        if (!strcmp(nm->name[i], s))
            return i;
    return -1;
}

int scene_parse_unknown(struct scene_parse *L, yaml_node_t *v, const char *what, const char *s,
                        const char *const *names, const char *expected)
{
    const char *near = ystr_nearest(s, names, -1);
    if (near)
        return ydoc_fail(&L->d, v, L->e, "%s \"%.40s\" (did you mean \"%s\"?)", what, s, near);
    return ydoc_fail(&L->d, v, L->e, "%s \"%.40s\" (expected %s)", what, s, expected);
}

int scene_parse_no_name(struct scene_parse *L, yaml_node_t *v, const char *key, const char *s,
                        const struct names *nm, const char *section)
{
    const char *near = ystr_nearest(s, nm->name, nm->n);
    if (near)
        return ydoc_fail(&L->d, v, L->e, "%s: no %s named \"%.40s\" in %s (did you mean \"%s\"?)", key, key,
                         s, section, near);
    return ydoc_fail(&L->d, v, L->e, "%s: no %s named \"%.40s\" in %s", key, key, s, section);
}

int scene_parse_color(struct scene_parse *L, yaml_node_t *v, const char *key, vec3 *out)
{
    if (yget_vec3(&L->d, v, key, out, L->e) < 0)
        return -1;
    if (out->x < 0 || out->y < 0 || out->z < 0)
        return ydoc_fail(&L->d, v, L->e, "%s: colour components must be >= 0", key);
    return 0;
}
