/* texture: solid checker (RTOW "The Next Week": the sign of sin(sx) sin(sy) sin(sz)). */
#include "texture.h"

vec3 texture_value(const struct texture *t, double u, double v, vec3 p)
{
    (void)u;
    (void)v;
    double s = sin(t->scale * p.x) * sin(t->scale * p.y) * sin(t->scale * p.z);
    return s < 0 ? t->odd : t->even;
}

int texture_needs_uv(const struct texture *t)
{
    (void)t;
    return 0;
}
