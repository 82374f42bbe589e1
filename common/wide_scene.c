/* wide_scene: which scenes the wide path tracer renders and its tables (wide_scene.h). */
#include "wide_scene.h"

#include <stdlib.h>
#include <string.h>

#include "shape_inline.h"

static int kind_of(const struct prim *p)
{
    return p->type == PRIM_RECT ? WK_RECT_X + p->g.rect.axis : p->type == PRIM_SPHERE ? WK_SPHERE : WK_BOX;
}

static void add_prim(struct wide_scene *ws, int p)
{
    const struct prim *pr = &ws->sc->prims[p];
    const struct material *m = &ws->sc->materials[pr->material];
    const int k = ws->n++;
    struct wide_prim *e = &ws->prims[k];
    struct wide_mat *wm = &ws->mats[k];
    double v[12] = {0};
    e->prim = p;
    wm->curved = 1;
    if (pr->type == PRIM_RECT) {
        e->kind = kind_of(pr);
        v[0] = pr->g.rect.k, v[1] = pr->g.rect.a0, v[2] = pr->g.rect.a1;
        v[3] = pr->g.rect.b0, v[4] = pr->g.rect.b1;
        wm->n[pr->g.rect.axis] = pr->flip ? -1 : 1; /* hit_rect's outward normal */
        wm->curved = 0;
    } else if (pr->type == PRIM_SPHERE) {
        e->kind = WK_SPHERE;
        const vec3 c = pr->g.sphere.center;
        const double r = pr->g.sphere.radius;
        v[0] = c.x, v[1] = c.y, v[2] = c.z, v[3] = r * r, v[4] = 1.0 / r;
    } else {
        e->kind = WK_BOX;
        const int x = pr->has_xform;
        v[0] = x ? pr->cos_y : 1, v[1] = x ? pr->sin_y : 0;
        v[2] = x ? pr->offset.x : 0, v[3] = x ? pr->offset.y : 0, v[4] = x ? pr->offset.z : 0;
        v[5] = pr->g.box.lo.x, v[6] = pr->g.box.lo.y, v[7] = pr->g.box.lo.z;
        v[8] = pr->g.box.hi.x, v[9] = pr->g.box.hi.y, v[10] = pr->g.box.hi.z;
    }
    for (int j = 0; j < 12; j++)
        e->v[j] = d4s(v[j]);
    wm->albedo[0] = m->albedo.x, wm->albedo[1] = m->albedo.y, wm->albedo[2] = m->albedo.z;
    wm->ior = m->ior;
    wm->emit[0] = m->emit.x, wm->emit[1] = m->emit.y, wm->emit[2] = m->emit.z;
    wm->type = m->type == MAT_LIGHT ? WM_EMIT : m->type == MAT_DIELECTRIC ? WM_DIELECTRIC : WM_LAMBERTIAN;
}

static void add_light(struct wide_light *l, const struct prim *p)
{
    memset(l, 0, sizeof *l);
    l->area = p->area;
    if (p->type == PRIM_SPHERE) {
        l->sphere = 1;
        l->c[0] = p->g.sphere.center.x, l->c[1] = p->g.sphere.center.y, l->c[2] = p->g.sphere.center.z;
        l->r2 = p->g.sphere.radius * p->g.sphere.radius;
        return;
    }
    l->on = p->g.rect.axis;
    rect_axes(l->on, &l->oa, &l->ob);
    l->k = p->g.rect.k, l->a0 = p->g.rect.a0, l->a1 = p->g.rect.a1, l->b0 = p->g.rect.b0, l->b1 = p->g.rect.b1;
    l->ball_c[0] = p->g.rect.ball_c.x, l->ball_c[1] = p->g.rect.ball_c.y, l->ball_c[2] = p->g.rect.ball_c.z;
    l->ball_r2 = p->g.rect.ball_r2, l->ball_r2_out = p->g.rect.ball_r2_out;
}

struct wide_scene *wide_scene_new(const struct scene *sc)
{
    struct wide_scene *ws = calloc(1, sizeof *ws);
    if (!ws)
        return NULL;
    ws->sc = sc;
    const size_t np = (size_t)sc->n_prims + 1;
    ws->prims = aligned_alloc(32, np * sizeof *ws->prims);
    ws->mats = aligned_alloc(32, np * sizeof *ws->mats);
    ws->lights = calloc((size_t)sc->n_lights + 1, sizeof *ws->lights);
    if (!ws->prims || !ws->mats || !ws->lights) {
        wide_scene_free(ws);
        return NULL;
    }
    memset(ws->mats, 0, np * sizeof *ws->mats);
    for (int kind = WK_RECT_X; kind <= WK_BOX; kind++) {
        for (int i = 0; i < sc->n_prims; i++)
            if (kind_of(&sc->prims[i]) == kind)
                add_prim(ws, i);
        ws->end[kind] = ws->n;
    }
    struct wide_mat *miss = &ws->mats[ws->n];
    miss->emit[0] = sc->background.x, miss->emit[1] = sc->background.y, miss->emit[2] = sc->background.z;
    miss->type = WM_EMIT;
    ws->n_lights = sc->n_lights;
    for (int i = 0; i < sc->n_lights; i++)
        add_light(&ws->lights[i], &sc->prims[sc->lights[i]]);
    return ws;
}

void wide_scene_free(struct wide_scene *ws)
{
    if (!ws)
        return;
    free(ws->prims);
    free(ws->mats);
    free(ws->lights);
    free(ws);
}

void wide_scene_hit(const struct wide_scene *ws, const double o[3][4], const double d[3][4], double t_min,
                    double t[4], int prim[4], double n[3][4])
{
    d4 o4[3], d4v[3], p[3], row[4], n4[3];
    for (int j = 0; j < 3; j++) {
        memcpy(&o4[j], o[j], sizeof o4[j]);
        memcpy(&d4v[j], d[j], sizeof d4v[j]);
    }
    const struct wide_best b = wide_hit(ws, o4, d4v, d4s(t_min));
    const void *rows[WIDE_LANES];
    for (int i = 0; i < WIDE_LANES; i++)
        rows[i] = &ws->mats[b.k[i] < 0 ? ws->n : b.k[i]];
    transpose4(rows, offsetof(struct wide_mat, n), row);
    for (int j = 0; j < 3; j++)
        p[j] = o4[j] + d4v[j] * b.t;
    wide_normal(ws, o4, d4v, p, b, row, n4);
    for (int i = 0; i < WIDE_LANES; i++) {
        t[i] = b.t[i];
        prim[i] = b.k[i] < 0 ? -1 : ws->prims[b.k[i]].prim;
        for (int j = 0; j < 3; j++)
            n[j][i] = n4[j][i];
    }
}
