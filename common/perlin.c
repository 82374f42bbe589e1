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

/* Two doubles in one vector register (a GCC/Clang extension, as bvh.c's float lanes). */
typedef double perlin_d2 __attribute__((vector_size(16)));

static int perlin_cell(double f)
{
    if (fabs(f) < 0x1.0p62)
        return (int)((int64_t)f & (PERLIN_N - 1));
    return (int)fmod(f, PERLIN_N);
}

/* perlin_noise's body, inline in perlin_turb's octaves (no call per octave). */
static inline __attribute__((always_inline)) double noise(const struct perlin *p, vec3 q)
{
    if (!v3_finite(q))
        return 0;
    double fx = floor(q.x), fy = floor(q.y), fz = floor(q.z);
    double u = q.x - fx, v = q.y - fy, w = q.z - fz;
    /* The table repeats at 256, so only the cell index modulo 256 matters: the low bits of an
       integer conversion where it is exact, fmod (slower) beyond. */
    int i = perlin_cell(fx), j = perlin_cell(fy), k = perlin_cell(fz);
    double uu = u * u * (3 - 2 * u), vv = v * v * (3 - 2 * v), ww = w * w * (3 - 2 * w);
    /* The corners' permutation entries, weights and offsets looked up or computed once, and
       the two corners of each (di, dj) evaluated side by side in one vector of two doubles: the
       book's terms, each rounded as the book rounds it, summed in its order. */
    const int px[2] = {p->perm_x[i], p->perm_x[(i + 1) & 255]},
              py[2] = {p->perm_y[j], p->perm_y[(j + 1) & 255]}, pz0 = p->perm_z[k],
              pz1 = p->perm_z[(k + 1) & 255];
    const double wx[2] = {1 - uu, uu}, wy[2] = {1 - vv, vv}, dx[2] = {u, u - 1}, dy[2] = {v, v - 1};
    const perlin_d2 wz = {1 - ww, ww}, dz = {w, w - 1};
    double accum = 0;
    for (int di = 0; di < 2; di++)
        for (int dj = 0; dj < 2; dj++) {
            const int pxy = px[di] ^ py[dj];
            const vec3 g0 = p->ranvec[pxy ^ pz0], g1 = p->ranvec[pxy ^ pz1];
            const perlin_d2 gx = {g0.x, g1.x}, gy = {g0.y, g1.y}, gz = {g0.z, g1.z};
            const double wxy = wx[di] * wy[dj];
            perlin_d2 t = wxy * wz * (gx * dx[di] + gy * dy[dj] + gz * dz);
            accum += t[0];
            accum += t[1];
        }
    return accum;
}

double perlin_noise(const struct perlin *p, vec3 q)
{
    return noise(p, q);
}

double perlin_turb(const struct perlin *p, vec3 q, int depth)
{
    double accum = 0, weight = 1;
    for (int i = 0; i < depth; i++) {
        accum += weight * noise(p, q);
        weight *= 0.5;
        q = v3_scale(q, 2);
    }
    return fabs(accum);
}
