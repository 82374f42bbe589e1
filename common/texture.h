/* texture: surface colour lookups (checker). */
#ifndef TEXTURE_H
#define TEXTURE_H

#include "scene.h"

/* Colour of texture t at surface coordinates (u, v) and point p. */
vec3 texture_value(const struct texture *t, double u, double v, vec3 p);

/* Whether t reads (u, v) (so the hit must compute them). */
int texture_needs_uv(const struct texture *t);

#endif
