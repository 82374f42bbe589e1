/* test_verdict_refnoise: the reference's own noise is taken out only when the reference is at least
   VERDICT_REF_FACTOR times denser than the densest point (a sparse one's halves miss the pixels
   where both agree by chance: refused, with one warning line), and a figure floored at 1% of its
   measured value is never floored silently. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "verdict_fixture.h"
#include "study/judge/verdict.h"

#define NS 4

static int any_line(char (*lines)[VERDICT_TEXT_MAX], int n, const char *text)
{
    for (int i = 0; i < n; i++)
        if (strstr(lines[i], text))
            return 1;
    return 0;
}

/* Two variants, relMSE 1 / spp (x a seed factor) plus the reference's 1e-3, at 100 and 400 spp. */
static void build(struct verdict_fixture *x, double ref_spp, double floor_one)
{
    static const double factor[NS] = {0.95, 1.0, 1.0, 1.05};
    verdict_fixture_init(x, "ref", 2, 2, NS, ref_spp);
    x->points[0] = "threshold 10", x->points[1] = "threshold 5";
    x->variants[0] = "alpha", x->variants[1] = "beta", x->samplers[0] = x->samplers[1] = "jitter";
    for (int v = 0; v < 2; v++)
        for (int p = 0; p < 2; p++) {
            x->rel_of_mean[v * 2 + p] = x->bias_rel[v * 2 + p] = NAN;
            for (int k = 0; k < NS; k++) {
                int i = verdict_at(&x->f, v, p, k);
                x->spp[i] = p ? 400 : 100, x->cpu[i] = x->spp[i] * 1e-5, x->radiance[i] = NAN;
                x->rel[i] = (v + 1.0) / x->spp[i] * factor[k] + 1e-3;
            }
        }
    x->rel[verdict_at(&x->f, 0, 1, 0)] = floor_one > 0 ? floor_one : x->rel[verdict_at(&x->f, 0, 1, 0)];
    x->f.ref.relmse = 1e-3;
}

int main(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    /* dense (4000 spp >= 4 x 400): taken out; alpha at 400 spp is its own 1/400 */
    build(&x, 4000, 0);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK_NEAR(s.point_rel[1], pow(0.95 * 1.05, 0.25) / 400, 1e-9);
    CHECK(!any_line(s.warnings, s.n_warnings, "too sparse"));
    CHECK(!any_line(s.warnings, s.n_warnings, "within the reference's own"));
    verdict_scene_free(&s);
    /* sparse (1000 spp < 4 x 400): refused, one line says so, the figures include its noise */
    build(&x, 1000, 0);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(any_line(s.warnings, s.n_warnings, "too sparse to take out"));
    CHECK(s.point_rel[1] > 1.0 / 400 + 0.9e-3);
    CHECK_NEAR(s.ref_relmse, 1e-3, 1e-15); /* still reported as measured */
    verdict_scene_free(&s);
    /* a figure at the reference's own noise: floored, and said */
    build(&x, 4000, 0.9e-3);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(any_line(s.warnings, s.n_warnings, "1 of 16 images' relMSE are within the reference's own 0.001"));
    verdict_scene_free(&s);
    return check_report("test_verdict_refnoise");
}
