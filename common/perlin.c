/* perlin: Perlin's gradient noise with Hermite-smoothed trilinear blending of gradient dot
   products, and turbulence as a sum of octaves (Shirley, "Ray Tracing: The Next Week", ch. 5). */
#include "perlin.h"

#include "rng.h"

static void permute(int *perm, struct rng *r)
{
    for (int i = 0; i < PERLIN_N; i++)
        perm[i] = i;
    for (int i = PERLIN_N - 1; i > 0; i--) { /* Fisher-Yates */
        int j = (int)rng_below(r, (uint32_t)i + 1);
        int t = perm[i];
        perm[i] = perm[j];
        perm[j] = t;
    }
}

void perlin_init(struct perlin *p, uint64_t seed)
{
    struct rng r;
    rng_seed(&r, seed, 0x70u);
    for (int i = 0; i < PERLIN_N; i++) {
        vec3 v;
        do {
            v = v3(2 * rng_uniform(&r) - 1, 2 * rng_uniform(&r) - 1, 2 * rng_uniform(&r) - 1);
        } while (v3_len2(v) < 1e-6 || v3_len2(v) > 1);
        p->ranvec[i] = v3_unit(v);
    }
    permute(p->perm_x, &r);
    permute(p->perm_y, &r);
    permute(p->perm_z, &r);
}

double perlin_noise(const struct perlin *p, vec3 q)
{
    if (!v3_finite(q))
        return 0;
    double fx = floor(q.x), fy = floor(q.y), fz = floor(q.z);
    double u = q.x - fx, v = q.y - fy, w = q.z - fz;
    /* fmod keeps the cell index in int range for any finite point; the table repeats at 256. */
    int i = (int)fmod(fx, PERLIN_N), j = (int)fmod(fy, PERLIN_N), k = (int)fmod(fz, PERLIN_N);
    double uu = u * u * (3 - 2 * u), vv = v * v * (3 - 2 * v), ww = w * w * (3 - 2 * w);
    double accum = 0;
    for (int di = 0; di < 2; di++)
        for (int dj = 0; dj < 2; dj++)
            for (int dk = 0; dk < 2; dk++) {
                vec3 g = p->ranvec[p->perm_x[(i + di) & 255] ^ p->perm_y[(j + dj) & 255] ^
                                   p->perm_z[(k + dk) & 255]];
                vec3 weight = v3(u - di, v - dj, w - dk);
                accum += (di ? uu : 1 - uu) * (dj ? vv : 1 - vv) * (dk ? ww : 1 - ww) * v3_dot(g, weight);
            }
    return accum;
}

double perlin_turb(const struct perlin *p, vec3 q, int depth)
{
    double accum = 0, weight = 1;
    for (int i = 0; i < depth; i++) {
        accum += weight * perlin_noise(p, q);
        weight *= 0.5;
        q = v3_scale(q, 2);
    }
    return fabs(accum);
}
