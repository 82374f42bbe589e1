/* wide_scene: which scenes the wide path tracer renders and its tables (wide_scene.h). */
#include "render_wide.h"

#if WIDE_KERNEL
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "shape.h"
#include "shape_inline.h"
#include "wide_scene.h"

static int kind_of(const struct prim *p)
{
    return p->type == PRIM_RECT ? WK_RECT_X + p->g.rect.axis : p->type == PRIM_SPHERE ? WK_SPHERE : WK_BOX;
}

static void set_col(struct wide_scene *ws, int c, int k, double x)
{
    ws->col[c][k >> 3][k & 7] = (float)x;
}

static void add_prim(struct wide_scene *ws, int p)
{
    const struct prim *pr = &ws->sc->prims[p];
    const struct material *m = &ws->sc->materials[pr->material];
    const int k = ws->n++;
    struct wide_prim *e = &ws->prims[k];
    double v[12] = {0};
    e->prim = p;
    e->kind = kind_of(pr);
    set_col(ws, WC_CURVED, k, pr->type != PRIM_RECT);
    const double *c0 = ws->centre;
    if (pr->type == PRIM_RECT) {
        int oa, ob;
        rect_axes(pr->g.rect.axis, &oa, &ob);
        v[0] = pr->g.rect.k - c0[pr->g.rect.axis], v[1] = pr->g.rect.a0 - c0[oa],
        v[2] = pr->g.rect.a1 - c0[oa];
        v[3] = pr->g.rect.b0 - c0[ob], v[4] = pr->g.rect.b1 - c0[ob];
        set_col(ws, WC_N + pr->g.rect.axis, k, pr->flip ? -1 : 1); /* hit_rect's outward normal */
    } else if (pr->type == PRIM_SPHERE) {
        const vec3 c = pr->g.sphere.center;
        const double r = pr->g.sphere.radius;
        v[0] = c.x - c0[0], v[1] = c.y - c0[1], v[2] = c.z - c0[2], v[3] = r * r, v[4] = 1.0 / r;
    } else {
        const int x = pr->has_xform;
        v[0] = x ? pr->cos_y : 1, v[1] = x ? pr->sin_y : 0;
        v[2] = (x ? pr->offset.x : 0) - c0[0], v[3] = (x ? pr->offset.y : 0) - c0[1];
        v[4] = (x ? pr->offset.z : 0) - c0[2];
        v[5] = pr->g.box.lo.x, v[6] = pr->g.box.lo.y, v[7] = pr->g.box.lo.z;
        v[8] = pr->g.box.hi.x, v[9] = pr->g.box.hi.y, v[10] = pr->g.box.hi.z;
    }
    for (int j = 0; j < 12; j++)
        e->v[j] = f8s((float)v[j]);
    set_col(ws, WC_ALBEDO, k, m->albedo.x), set_col(ws, WC_ALBEDO + 1, k, m->albedo.y);
    set_col(ws, WC_ALBEDO + 2, k, m->albedo.z), set_col(ws, WC_IOR, k, m->ior);
    set_col(ws, WC_EMIT, k, m->emit.x), set_col(ws, WC_EMIT + 1, k, m->emit.y);
    set_col(ws, WC_EMIT + 2, k, m->emit.z);
    set_col(ws, WC_TYPE, k,
            m->type == MAT_LIGHT        ? WM_EMIT
            : m->type == MAT_DIELECTRIC ? WM_DIELECTRIC
                                        : WM_LAMBERTIAN);
}

static void add_light(struct wide_light *l, const struct prim *p, const double c0[3])
{
    memset(l, 0, sizeof *l);
    l->area = (float)p->area;
    if (p->type == PRIM_SPHERE) {
        l->sphere = 1;
        l->c[0] = (float)(p->g.sphere.center.x - c0[0]), l->c[1] = (float)(p->g.sphere.center.y - c0[1]);
        l->c[2] = (float)(p->g.sphere.center.z - c0[2]);
        l->r2 = (float)(p->g.sphere.radius * p->g.sphere.radius);
        return;
    }
    l->on = p->g.rect.axis;
    rect_axes(l->on, &l->oa, &l->ob);
    l->k = (float)(p->g.rect.k - c0[l->on]);
    l->a0 = (float)(p->g.rect.a0 - c0[l->oa]), l->a1 = (float)(p->g.rect.a1 - c0[l->oa]);
    l->b0 = (float)(p->g.rect.b0 - c0[l->ob]), l->b1 = (float)(p->g.rect.b1 - c0[l->ob]);
}

struct wide_scene *wide_scene_new(const struct scene *sc)
{
    if (sc->n_prims > WIDE_MAX_PRIMS || sc->n_lights > WIDE_MAX_LIGHTS)
        return NULL;
    struct wide_scene *ws = aligned_alloc(32, sizeof *ws);
    if (!ws)
        return NULL;
    memset(ws, 0, sizeof *ws);
    ws->sc = sc;
    ws->prims = aligned_alloc(32, ((size_t)sc->n_prims + 1) * sizeof *ws->prims);
    ws->lights = calloc((size_t)sc->n_lights + 1, sizeof *ws->lights);
    if (!ws->prims || !ws->lights) {
        wide_scene_free(ws);
        return NULL;
    }
    vec3 lo = v3(INFINITY, INFINITY, INFINITY), hi = v3(-INFINITY, -INFINITY, -INFINITY);
    for (int i = 0; i < sc->n_prims; i++) {
        vec3 pl, ph;
        shape_bounds(&sc->prims[i], &pl, &ph);
        lo = v3(fmin(lo.x, pl.x), fmin(lo.y, pl.y), fmin(lo.z, pl.z));
        hi = v3(fmax(hi.x, ph.x), fmax(hi.y, ph.y), fmax(hi.z, ph.z));
    }
    const vec3 mid = v3_scale(v3_add(lo, hi), 0.5);
    ws->centre[0] = mid.x, ws->centre[1] = mid.y, ws->centre[2] = mid.z;
    ws->radius = sc->n_prims > 0 ? v3_len(v3_sub(hi, mid)) : 0;
    for (int kind = WK_RECT_X; kind <= WK_BOX; kind++) {
        for (int i = 0; i < sc->n_prims; i++)
            if (kind_of(&sc->prims[i]) == kind)
                add_prim(ws, i);
        ws->end[kind] = ws->n;
    }
    set_col(ws, WC_EMIT, ws->n, sc->background.x), set_col(ws, WC_EMIT + 1, ws->n, sc->background.y);
    set_col(ws, WC_EMIT + 2, ws->n, sc->background.z), set_col(ws, WC_TYPE, ws->n, WM_EMIT);
    ws->n_lights = sc->n_lights;
    for (int i = 0; i < sc->n_lights; i++)
        add_light(&ws->lights[i], &sc->prims[sc->lights[i]], ws->centre);
    return ws;
}

void wide_scene_free(struct wide_scene *ws)
{
    if (!ws)
        return;
    free(ws->prims);
    free(ws->lights);
    free(ws);
}

void wide_scene_hit(const struct wide_scene *ws, const double *o, const double *d, double t_min, double *t,
                    int *prim, double *n)
{
    f8 o8[3], d8[3], p[3], n8[3];
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < WIDE_LANES; i++)
            o8[j][i] = (float)(o[j * WIDE_LANES + i] - ws->centre[j]),
            d8[j][i] = (float)d[j * WIDE_LANES + i];
    const struct wide_best b = wide_hit(ws, o8, d8, f8s((float)t_min));
    const i8 k = picki(b.k < 0, i8s(ws->n), b.k);
    for (int j = 0; j < 3; j++)
        p[j] = o8[j] + d8[j] * b.t;
    wide_normal(ws, o8, d8, p, b, k, n8);
    for (int i = 0; i < WIDE_LANES; i++) {
        t[i] = b.t[i];
        prim[i] = b.k[i] < 0 ? -1 : ws->prims[b.k[i]].prim;
        for (int j = 0; j < 3; j++)
            n[j * WIDE_LANES + i] = n8[j][i];
    }
}
#else
/* Without the kernel wide_usable is 0, so none of these is ever called: reaching one is a bug. */
#include <stdlib.h>

struct wide_scene *wide_scene_new(const struct scene *sc)
{
    abort();
}

void wide_scene_free(struct wide_scene *ws)
{
    abort();
}

void wide_scene_hit(const struct wide_scene *ws, const double *o, const double *d, double t_min, double *t,
                    int *prim, double *n)
{
    abort();
}
#endif
