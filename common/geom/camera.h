/* camera: the RTOW thin-lens camera with a shutter interval. */
#ifndef CAMERA_H
#define CAMERA_H

#include "base/err.h"
#include "base/rng.h"
#include "base/vec3.h"

struct camera_desc {
    vec3 lookfrom, lookat, vup;
    double vfov_deg, aperture, focus_dist;
    double shutter0, shutter1;
};

struct camera {
    vec3 origin, lower_left, horizontal, vertical;
    vec3 u, v, w;
    double lens_radius;
    double time0, time1;
};

/* Set up cam for an image of the given aspect (width / height). -1 with e filled when the
   description is degenerate (lookfrom == lookat, vup parallel to the view, vfov out of (0,180)). */
int camera_init(struct camera *cam, const struct camera_desc *d, double aspect, struct err *e);

/* The ray through film point (s, t) in [0,1]^2 (s rightwards, t upwards) from the lens point of
   uniforms (lu, lv) (unused without a lens) at the shutter time of uniform tu (unused with the
   shutter closed). Inline: one per camera sample, and a call passed the ray back through memory. */
static inline __attribute__((always_inline)) ray camera_ray_at(const struct camera *cam, double s, double t,
                                                               double lu, double lv, double tu)
{
    vec3 origin = cam->origin;
    if (cam->lens_radius > 0) {
        /* Uniform point on the lens disk by area: r = R sqrt(u), angle 2 pi v. */
        double r = cam->lens_radius * sqrt(lu), sin_a, cos_a;
        v3_sincos_turn(lv, &sin_a, &cos_a);
        origin = v3_add(origin, v3_add(v3_scale(cam->u, r * cos_a), v3_scale(cam->v, r * sin_a)));
    }
    vec3 target = v3_add(v3_add(cam->lower_left, v3_scale(cam->horizontal, s)), v3_scale(cam->vertical, t));
    ray out;
    out.orig = origin;
    out.dir = v3_sub(target, origin);
    out.time = cam->time0 == cam->time1 ? cam->time0 : cam->time0 + tu * (cam->time1 - cam->time0);
    return out;
}

/* camera_ray_at with the lens point and the time drawn from rng (only those it uses). */
static inline __attribute__((always_inline)) ray camera_ray(const struct camera *cam, double s, double t,
                                                            struct rng *rng)
{
    double lu = 0, lv = 0, tu = 0;
    if (cam->lens_radius > 0) {
        lu = rng_uniform32(rng);
        lv = rng_uniform32(rng);
    }
    if (cam->time0 != cam->time1)
        tu = rng_uniform32(rng);
    return camera_ray_at(cam, s, t, lu, lv, tu);
}

#endif
