/* test_zsobol: a pixel's Z-Sobol set is one aligned block of the Sobol sequence's indices and a
   (0,m,2)-net; four pixels of one Morton quad together form the next net (the hierarchy that
   spreads the error as blue noise); sets are deterministic and differ between dimensions and seeds
   (test_sobol checks the 64-bit index's second coordinate). */
#include "sample/zsobol.h"

#include <stdlib.h>

#include "check.h"
#include "sample/pointstat.h"

static void test_blocks_and_nets(void)
{
    struct pt2 p[4 * 1024];
    int blocks = 1, nets = 1, quads = 1;
    for (int m = 0; m <= 10; m++)
        for (uint32_t px = 0; px < 6; px++) {
            struct zsobol_key k = {17 + (uint64_t)m, (uint32_t)m % 3, px * 37, px * 11 + 5, m};
            const uint32_t n = (uint32_t)1 << m;
            uint64_t first = zsobol_index(k, 0) >> m;
            for (uint32_t i = 0; i < n; i++)
                blocks &= zsobol_index(k, i) >> m == first;
            zsobol_fill(k, p);
            nets &= pointstat_is_net(p, n) == 1;
            /* the Morton quad holding this pixel: its four pixels' sets, one net of 4n */
            for (uint32_t q = 0; q < 4; q++) {
                struct zsobol_key kq = k;
                kq.x = (k.x & ~1u) | (q & 1u);
                kq.y = (k.y & ~1u) | (q >> 1);
                zsobol_fill(kq, p + q * n);
            }
            quads &= pointstat_is_net(p, 4 * n) == 1;
        }
    CHECK(blocks);
    CHECK(nets);
    CHECK(quads);
    /* the checks can fail: a quad of pixels from different dimensions is no net */
    struct zsobol_key a = {3, 0, 8, 8, 4}, b = a;
    zsobol_fill(a, p);
    b.dim = 1;
    for (uint32_t q = 1; q < 4; q++) {
        b.x = 8 | (q & 1u);
        b.y = 8 | (q >> 1);
        b.dim = q;
        zsobol_fill(b, p + q * 16);
    }
    CHECK(pointstat_is_net(p, 64) == 0);
}

static void test_keys(void)
{
    struct zsobol_key k = {42, 0, 5, 9, 6};
    struct pt2 a[64], b[64];
    zsobol_fill(k, a);
    zsobol_fill(k, b);
    int same = 1;
    for (int i = 0; i < 64; i++)
        same &= a[i].x == b[i].x && a[i].y == b[i].y;
    CHECK(same);
    k.dim = 1;
    zsobol_fill(k, b);
    CHECK(a[0].x != b[0].x || a[0].y != b[0].y);
    k.dim = 0;
    k.seed = 43;
    zsobol_fill(k, b);
    CHECK(a[0].x != b[0].x || a[0].y != b[0].y);
    /* an odd power of two: still a net */
    k.log2_spp = 7;
    struct pt2 c[128];
    zsobol_fill(k, c);
    CHECK(pointstat_is_net(c, 128) == 1);
}

int main(void)
{
    test_blocks_and_nets();
    test_keys();
    return check_report("test_zsobol");
}
