/* shape_bake: a prim's derived fields (shape_prepare) and the rotate_y + translate folded into its
   geometry at load where the shape allows (shape_bake); shape.c tests the rays. */
#include <math.h>

#include "shape.h"
#include "shape_inline.h"

void shape_prepare(struct prim *p)
{
    if (p->type == PRIM_RECT) {
        int ax = p->g.rect.axis, a, b;
        rect_axes(ax, &a, &b);
        p->g.rect.n = v3(ax == 0, ax == 1, ax == 2);
        p->g.rect.ea = v3(a == 0, a == 1, a == 2);
        p->g.rect.eb = v3(b == 0, b == 1, b == 2);
        p->g.rect.on = ax * (long)sizeof(double);
        p->g.rect.oa = a * (long)sizeof(double);
        p->g.rect.ob = b * (long)sizeof(double);
        /* the unit axes have one non-zero component each: the centre's sum is exact */
        double da = p->g.rect.a1 - p->g.rect.a0, db = p->g.rect.b1 - p->g.rect.b0;
        p->g.rect.ball_c = v3_add(
            v3_add(v3_scale(p->g.rect.n, p->g.rect.k), v3_scale(p->g.rect.ea, p->g.rect.a0 + 0.5 * da)),
            v3_scale(p->g.rect.eb, p->g.rect.b0 + 0.5 * db));
        p->g.rect.ball_r2 = (da * da + db * db) * (0.25 * (1 + 1e-9));
        p->g.rect.ball_r2_out = p->g.rect.ball_r2 * (1 + 1e-6);
    }
    if (p->type == PRIM_MEDIUM) {
        p->g.medium.hash_key = medium_hash_key(p);
        p->g.medium.mean_free_lo = -p->g.medium.neg_inv_density * (1 - 1e-9);
    }
    if (p->type == PRIM_DISK) {
        p->g.disk.r2 = p->g.disk.radius * p->g.disk.radius;
        p->g.disk.r2_out = p->g.disk.r2 * (1 + 1e-6);
    }
    p->area = shape_area(p);
}

int shape_bakes(const struct prim *p, int keep_uv)
{
    if (!p->has_xform)
        return 0;
    switch (p->type) {
    case PRIM_SPHERE: /* its uv is its object-space direction: turned, the texture would turn */
        return !keep_uv;
    case PRIM_RECT: /* axis-aligned after quarter turns alone (cos or sin 0 to rounding); its uv turns */
        return !keep_uv && (fabs(p->cos_y) < 1e-12 || fabs(p->sin_y) < 1e-12);
    case PRIM_MOVING_SPHERE:
    case PRIM_DISK: /* its frame turns with it: the same uv */
    case PRIM_CYLINDER:
    case PRIM_TRIANGLE:
        return 1;
    default: /* boxes stay axis-aligned in object space; media hash the object-space ray */
        return 0;
    }
}

/* A rect turned a quarter turn k times about y and moved is again an axis-aligned rect: its
   corners and normal turned by the exact rotation (cos, sin rounded to 0 or +-1) and moved. */
static void rect_bake(struct prim *p)
{
    struct prim q = *p; /* the exact quarter turn */
    q.cos_y = round(p->cos_y), q.sin_y = round(p->sin_y);
    int ax = p->g.rect.axis, a, b;
    rect_axes(ax, &a, &b);
    double lo[3], hi[3], n[3] = {0, 0, 0};
    lo[ax] = hi[ax] = p->g.rect.k;
    lo[a] = p->g.rect.a0, hi[a] = p->g.rect.a1;
    lo[b] = p->g.rect.b0, hi[b] = p->g.rect.b1;
    n[ax] = p->flip ? -1 : 1;
    vec3 wl = point_to_world(&q, v3(lo[0], lo[1], lo[2])), wh = point_to_world(&q, v3(hi[0], hi[1], hi[2]));
    vec3 wn = rotate_to_world(&q, v3(n[0], n[1], n[2]));
    int nax = fabs(wn.x) > 0.5 ? 0 : fabs(wn.y) > 0.5 ? 1 : 2, na, nb;
    rect_axes(nax, &na, &nb);
    p->g.rect.axis = nax;
    p->flip = v3_get(wn, nax) < 0;
    p->g.rect.k = v3_get(wl, nax);
    p->g.rect.a0 = fmin(v3_get(wl, na), v3_get(wh, na)), p->g.rect.a1 = fmax(v3_get(wl, na), v3_get(wh, na));
    p->g.rect.b0 = fmin(v3_get(wl, nb), v3_get(wh, nb)), p->g.rect.b1 = fmax(v3_get(wl, nb), v3_get(wh, nb));
}

int shape_bake(struct prim *p, int keep_uv)
{
    if (!shape_bakes(p, keep_uv))
        return 0;
    switch (p->type) {
    case PRIM_SPHERE:
        p->g.sphere.center = point_to_world(p, p->g.sphere.center);
        break;
    case PRIM_RECT:
        rect_bake(p);
        break;
    case PRIM_MOVING_SPHERE:
        p->g.msphere.center0 = point_to_world(p, p->g.msphere.center0);
        p->g.msphere.velocity = rotate_to_world(p, p->g.msphere.velocity);
        break;
    case PRIM_DISK:
        p->g.disk.center = point_to_world(p, p->g.disk.center);
        p->g.disk.normal = rotate_to_world(p, p->g.disk.normal);
        p->g.disk.e1 = rotate_to_world(p, p->g.disk.e1);
        p->g.disk.e2 = rotate_to_world(p, p->g.disk.e2);
        break;
    case PRIM_CYLINDER:
        p->g.cyl.base = point_to_world(p, p->g.cyl.base);
        p->g.cyl.axis = rotate_to_world(p, p->g.cyl.axis);
        break;
    case PRIM_TRIANGLE:
        p->g.tri.v0 = point_to_world(p, p->g.tri.v0);
        p->g.tri.e1 = rotate_to_world(p, p->g.tri.e1);
        p->g.tri.e2 = rotate_to_world(p, p->g.tri.e2);
        p->g.tri.normal = rotate_to_world(p, p->g.tri.normal);
        break;
    default:
        return 0;
    }
    p->has_xform = 0;
    p->cos_y = 1, p->sin_y = 0, p->offset = v3(0, 0, 0);
    shape_prepare(p);
    return 1;
}
