/* camera: thin-lens ray generation (Shirley, "Ray Tracing in One Weekend", defocus blur). */
#include "camera.h"

int camera_init(struct camera *cam, const struct camera_desc *d, double aspect, struct err *e)
{
    if (!(d->vfov_deg > 0 && d->vfov_deg < 180))
        return err_set(e, NULL, 0, 0, "vfov must be in (0, 180), got %g", d->vfov_deg);
    vec3 back = v3_sub(d->lookfrom, d->lookat);
    if (v3_len(back) == 0)
        return err_set(e, NULL, 0, 0, "lookfrom and lookat are the same point");
    vec3 w = v3_unit(back);
    vec3 side = v3_cross(d->vup, w);
    if (v3_len(side) < 1e-9 * (v3_len(d->vup) + 1e-300))
        return err_set(e, NULL, 0, 0, "vup is parallel to the viewing direction");
    if (!(d->focus_dist > 0))
        return err_set(e, NULL, 0, 0, "focus_dist must be positive, got %g", d->focus_dist);
    double h = tan(d->vfov_deg * PI / 180.0 / 2);
    double vh = 2.0 * h, vw = aspect * vh;
    cam->w = w;
    cam->u = v3_unit(side);
    cam->v = v3_cross(w, cam->u);
    cam->origin = d->lookfrom;
    cam->horizontal = v3_scale(cam->u, d->focus_dist * vw);
    cam->vertical = v3_scale(cam->v, d->focus_dist * vh);
    cam->lower_left =
        v3_sub(v3_sub(v3_sub(cam->origin, v3_scale(cam->horizontal, 0.5)), v3_scale(cam->vertical, 0.5)),
               v3_scale(w, d->focus_dist));
    cam->lens_radius = d->aperture / 2;
    cam->time0 = d->shutter0;
    cam->time1 = d->shutter1;
    return 0;
}
