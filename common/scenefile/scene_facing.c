/* scene_facing: finding a light that faces away from everything it could light (a disk's toward:
   or a rect's flip: the wrong way), named with its place in the scene file. */
#include <stdio.h>

#include "geom/shape.h"
#include "scene_parse.h"

/* Whether any corner of the box lo..hi lies in front of the plane through c with normal nf,
   beyond a margin relative to the box's size (a box touching the plane from behind is behind). */
static int box_in_front(vec3 lo, vec3 hi, vec3 c, vec3 nf)
{
    double margin = 1e-9 * (1 + v3_len(v3_sub(hi, lo)));
    for (int k = 0; k < 8; k++) {
        vec3 q = v3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
        if (v3_dot(v3_sub(q, c), nf) > margin)
            return 1;
    }
    return 0;
}

/* Whether light prim p (a baked rect or disk) has anything in front of its emitting face. */
static int lights_something(const struct scene *sc, const struct prim *p, vec3 eye)
{
    vec3 c, nf;
    if (p->type == PRIM_DISK) {
        c = p->g.disk.center;
        nf = p->g.disk.normal;
    } else {
        nf = p->flip ? v3_neg(p->g.rect.n) : p->g.rect.n;
        c = v3_scale(p->g.rect.n, p->g.rect.k);
    }
    if (box_in_front(eye, eye, c, nf))
        return 1;
    for (int i = 0; i < sc->n_prims; i++) {
        const struct prim *q = &sc->prims[i];
        if (sc->materials[q->material].type == MAT_LIGHT)
            continue; /* a light reflects nothing */
        vec3 lo, hi;
        shape_bounds(q, &lo, &hi);
        if (box_in_front(lo, hi, c, nf))
            return 1;
    }
    return 0;
}

void scene_parse_facing_away(const struct scene_parse *L, char *buf, size_t n)
{
    const struct scene *sc = L->sc;
    buf[0] = 0;
    for (int i = 0; i < sc->n_lights; i++) {
        const struct prim *p = &sc->prims[sc->lights[i]];
        if (sc->materials[p->material].type != MAT_LIGHT || (p->type != PRIM_DISK && p->type != PRIM_RECT) ||
            p->has_xform || lights_something(sc, p, L->cam->lookfrom))
            continue;
        const char *mat = p->material < L->mat.n ? L->mat.name[p->material] : "?";
        snprintf(
            buf, n,
            "%s:%d:%d: the %s light (material \"%s\") faces away from everything in the scene and lights "
            "nothing: %s",
            L->d.file, L->light_pos[i][0], L->light_pos[i][1], p->type == PRIM_DISK ? "disk" : "rect", mat,
            p->type == PRIM_DISK ? "a disk emits toward its toward: point"
                                 : "a rect emits from its front face "
                                   "(flip: true turns it)");
        return;
    }
}
