/* camera: the RTOW thin-lens camera with a shutter interval. */
#ifndef CAMERA_H
#define CAMERA_H

#include "err.h"
#include "rng.h"
#include "vec3.h"

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

/* The ray through film point (s, t) in [0,1]^2, s rightwards, t upwards; lens and time from rng. */
ray camera_ray(const struct camera *cam, double s, double t, struct rng *rng);

#endif
