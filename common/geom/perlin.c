/* perlin: Perlin's gradient noise with Hermite-smoothed trilinear blending of gradient dot
   products, and turbulence as a sum of octaves (Shirley, "Ray Tracing: The Next Week", ch. 5). */
#include "perlin.h"

#include "base/rng.h"

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
            /* one draw a declarator: a call's arguments have no order in C (gcc took them last
               first, clang first first); z, y, x keeps the images gcc made */
            double z = 2 * rng_uniform(&r) - 1, y = 2 * rng_uniform(&r) - 1, x = 2 * rng_uniform(&r) - 1;
            v = v3(x, y, z);
        } while (v3_len2(v) < 1e-6 || v3_len2(v) > 1);
        p->ranvec[i] = v3_unit(v);
    }
    permute(p->perm_x, &r);
    permute(p->perm_y, &r);
    permute(p->perm_z, &r);
    for (int i = 0; i <= PERLIN_N; i++) {
        const int n = i & (PERLIN_N - 1);
        double *g = p->grad + 4 * n;
        g[0] = p->ranvec[n].x, g[1] = p->ranvec[n].y, g[2] = p->ranvec[n].z, g[3] = 0;
        p->off_x[i] = 4 * (unsigned)p->perm_x[n];
        p->off_y[i] = 4 * (unsigned)p->perm_y[n];
        p->off_z[i] = 4 * (unsigned)p->perm_z[n];
    }
}

/* Two doubles in one vector register (a GCC/Clang extension, as bvh.c's float lanes). */
typedef double perlin_d2 __attribute__((vector_size(16)));

static unsigned perlin_cell(double f)
{
    if (fabs(f) < 0x1.0p62)
        return (unsigned)((int64_t)f & (PERLIN_N - 1));
    return (unsigned)fabs(fmod(f, PERLIN_N)); /* 0: such f are multiples of 1024 */
}

/* A cell's two z sides (dk = 0, 1), shared by its four (di, dj): their permutation indices, their
   weights and the offsets from them. */
struct cell_z {
    unsigned pz0, pz1;
    perlin_d2 wz, dz;
};

/* The two corners (dk = 0, 1) of one (di, dj) of a cell side by side in one vector of two
   doubles: weight wxy wz times the gradient's dot with the corner's offset, each rounded as the
   book rounds it. */
static inline perlin_d2 corner_pair(const struct perlin *p, unsigned pxy, struct cell_z z, double wxy,
                                    double dx, double dy)
{
    const double *g0 = p->grad + (pxy ^ z.pz0), *g1 = p->grad + (pxy ^ z.pz1);
    const perlin_d2 gx = {g0[0], g1[0]}, gy = {g0[1], g1[1]}, gz = {g0[2], g1[2]};
    return wxy * z.wz * (gx * dx + gy * dy + gz * z.dz);
}

/* The eight corners' sum of the cell whose permutation indices are (i, j, k) (already reduced
   to the table) at offsets (u, v, w) within it: the book's terms summed in its order, the
   corners' entries, weights and offsets looked up or computed once, the four (di, dj) written
   out (no loop, no arrays on the stack). The book's sum starts from +0; this one from the first
   term, which differs only where every partial sum is zero, and then only in the zero's sign. */
static inline __attribute__((always_inline)) double cell_sum(const struct perlin *p, unsigned i, unsigned j,
                                                             unsigned k, double u, double v, double w)
{
    double uu = u * u * (3 - 2 * u), vv = v * v * (3 - 2 * v), ww = w * w * (3 - 2 * w);
    const unsigned px0 = p->off_x[i], px1 = p->off_x[i + 1], py0 = p->off_y[j], py1 = p->off_y[j + 1],
                   pz0 = p->off_z[k], pz1 = p->off_z[k + 1];
    const double wx0 = 1 - uu, wy0 = 1 - vv, dx1 = u - 1, dy1 = v - 1;
    const struct cell_z z = {pz0, pz1, {1 - ww, ww}, {w, w - 1}};
    perlin_d2 t = corner_pair(p, px0 ^ py0, z, wx0 * wy0, u, v);
    double accum = t[0];
    accum += t[1];
    t = corner_pair(p, px0 ^ py1, z, wx0 * vv, u, dy1);
    accum += t[0];
    accum += t[1];
    t = corner_pair(p, px1 ^ py0, z, uu * wy0, dx1, v);
    accum += t[0];
    accum += t[1];
    t = corner_pair(p, px1 ^ py1, z, uu * vv, dx1, dy1);
    accum += t[0];
    accum += t[1];
    return accum;
}

double perlin_noise(const struct perlin *p, vec3 q)
{
    if (!v3_finite(q))
        return 0;
    double fx = floor(q.x), fy = floor(q.y), fz = floor(q.z);
    /* The table repeats at 256, so only the cell index modulo 256 matters: the low bits of an
       integer conversion where it is exact, fmod (slower) beyond. */
    /* 0 + s: the book's +0 where cell_sum's zero came out -0 (+0 + s is s for any other s) */
    return 0.0 + cell_sum(p, perlin_cell(fx), perlin_cell(fy), perlin_cell(fz), q.x - fx, q.y - fy, q.z - fz);
}

/* Whether every octave's cell and offset follow exactly from the first's: x - floor(x) is exact
   for x >= 0 (x itself below 1, else a multiple of x's ulp >= 2^-52 below 1) and for x <= -1
   (likewise), not in (-1, 0), where 1 - |x| may round; 2^32 keeps 2^depth floor(x) far inside
   an int64 for the octaves that matter and rules out non-finite x. */
static int octaves_exact(double x)
{
    return (x >= 0 || x <= -1) && fabs(x) < 0x1.0p32;
}

double perlin_turb(const struct perlin *p, vec3 q, int depth)
{
    double accum = 0, weight = 1;
    if (depth > 0 && depth <= 20 && octaves_exact(q.x) && octaves_exact(q.y) && octaves_exact(q.z)) {
        /* One floor per axis: at twice the point, the cell is 2 floor(x) + b and the offset
           2 u - b, b = (u >= 1/2), both exact (2 u - 1 in [0, 1) by Sterbenz), so each octave
           gets the very cell and offset the book's floor of 2^o x gives. An octave's noise may
           differ from the book's in the sign of a zero (cell_sum), which fabs does not see. */
        double fx = floor(q.x), fy = floor(q.y), fz = floor(q.z);
        double u = q.x - fx, v = q.y - fy, w = q.z - fz;
        unsigned i = (unsigned)((int64_t)fx & 255), j = (unsigned)((int64_t)fy & 255),
                 k = (unsigned)((int64_t)fz & 255);
        for (int o = 0; o < depth; o++) {
            accum += weight * cell_sum(p, i, j, k, u, v, w);
            weight *= 0.5;
            const unsigned bi = u >= 0.5, bj = v >= 0.5, bk = w >= 0.5;
            i = (2 * i + bi) & 255, j = (2 * j + bj) & 255, k = (2 * k + bk) & 255;
            u = 2 * u - bi, v = 2 * v - bj, w = 2 * w - bk;
        }
        return fabs(accum);
    }
    for (int o = 0; o < depth; o++) {
        accum += weight * perlin_noise(p, q);
        weight *= 0.5;
        q = v3_scale(q, 2);
    }
    return fabs(accum);
}
