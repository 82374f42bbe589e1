/* test_dims: sampler_dims: all's grid sets. The keyed permutation is a bijection of [0, n) for
   any n; a jitter or uniform set gives the pixel's n samples one point in each cell; different
   slots and keys give different orders. */
#include <stdlib.h>

#include "check.h"
#include "render/render_internal.h"

static int is_bijection(uint32_t n, uint64_t key)
{
    unsigned char *seen = calloc(n, 1);
    int ok = seen != NULL;
    for (uint32_t i = 0; ok && i < n; i++) {
        uint32_t p = render_dims_permute(i, n, key);
        ok = p < n && !seen[p];
        if (ok)
            seen[p] = 1;
    }
    free(seen);
    return ok;
}

/* Every cell of the n x n grid holds exactly one of slot's points for samples 0..n*n-1. */
static int one_per_cell(struct render_ctx *ctx, int slot)
{
    const int n = ctx->dims_grid.n;
    int *count = calloc((size_t)n * (size_t)n, sizeof *count), ok = count != NULL;
    for (uint32_t s = 0; ok && s < (uint32_t)(n * n); s++) {
        struct pt2 p = render_dims_grid_point(ctx, slot, s);
        ok = p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1;
        if (ok)
            count[(int)(p.y * n) * n + (int)(p.x * n)]++;
    }
    for (int c = 0; ok && c < n * n; c++)
        ok = count[c] == 1;
    free(count);
    return ok;
}

int main(void)
{
    static const uint32_t sizes[] = {1, 2, 3, 4, 7, 64, 100, 400, 1000, 6241, 10000};
    for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++)
        for (uint64_t key = 1; key < 6; key++)
            CHECK(is_bijection(sizes[k], key * 0x9e3779b97f4a7c15ULL));
    /* different keys give different orders */
    int differ = 0;
    for (uint32_t i = 0; i < 400; i++)
        differ += render_dims_permute(i, 400, 1) != render_dims_permute(i, 400, 2);
    CHECK(differ > 300);

    struct err e;
    const enum sampler_kind kinds[] = {SAMPLER_JITTER, SAMPLER_UNIFORM};
    for (int k = 0; k < 2; k++) {
        struct sampler *s = sampler_new(kinds[k], 10, 0, 0, &e); /* 10 x 10 */
        struct render_ctx ctx = {0};
        CHECK(s != NULL);
        if (!s)
            continue;
        ctx.dims_grid = sampler_grid_of(s);
        ctx.dims_grid_sets = 1;
        for (uint64_t key = 1; key < 4; key++) {
            ctx.dims_key = key;
            for (int slot = 0; slot < 5; slot++)
                CHECK(one_per_cell(&ctx, slot));
        }
        /* two slots of one pixel put sample 0 in different cells for most keys */
        int apart = 0;
        for (uint64_t key = 1; key <= 100; key++) {
            ctx.dims_key = key;
            struct pt2 a = render_dims_grid_point(&ctx, 2, 0), b = render_dims_grid_point(&ctx, 3, 0);
            apart += (int)(a.x * 10) != (int)(b.x * 10) || (int)(a.y * 10) != (int)(b.y * 10);
        }
        CHECK(apart > 90);
        sampler_free(s);
    }
    return check_report("test_dims");
}
