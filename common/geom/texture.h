/* texture: surface colour lookups (checker, Perlin marble, image). */
#ifndef TEXTURE_H
#define TEXTURE_H

#include "geom_types.h"

/* Colour of texture t of scene sc at surface coordinates (u, v) and world point p. */
vec3 texture_value(const struct scene *sc, const struct texture *t, double u, double v, vec3 p);

/* Whether t reads (u, v) (so the hit must compute them). */
int texture_needs_uv(const struct texture *t);

#endif
