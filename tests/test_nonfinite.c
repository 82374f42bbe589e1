/* test_nonfinite: a NaN or infinite sample counts as zero and the pixel divides by all its
   samples (pbrt's rule), and render_stats counts it. In tests/data/nonfinite.yaml every finite
   sample is exactly 0 or 1 in green, so a pixel's green times its sample count is the whole
   number of its samples on the patch: true when it divides by all n, false (m n / (n - k)) when
   it drops its k non-finite samples as before issue 26. */
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "render/render.h"
#include "scenefile/scene_load.h"

#define SIDE 12

int main(void)
{
    struct scene_file sf;
    struct err e;
    if (scene_load("tests/data/nonfinite.yaml", &sf, &e) < 0) {
        fprintf(stderr, "%s\n", e.msg);
        CHECK(0);
        return check_report("test_nonfinite");
    }
    struct camera cam;
    CHECK(camera_init(&cam, &sf.camera, 1.0, &e) == 0);
    struct sampler *pix = sampler_new(SAMPLER_JITTER, 10, 0, 0, &e); /* 100 samples a pixel */
    struct render_settings rs = {SIDE, SIDE, 50, 1, 1, 0, 0, 0};     /* light sampling off */
    struct render_ctx *ctx = pix ? render_ctx_new(sf.scene, &cam, &rs, pix, NULL, &e) : NULL;
    CHECK(ctx != NULL);
    int finite = 1, whole = 1, mixed = 0;
    struct render_stats st;
    render_stats_init(&st);
    for (int y = 0; ctx && y < SIDE; y++)
        for (int x = 0; x < SIDE; x++) {
            float c[3];
            const uint64_t before = st.nonfinite;
            render_pixel(ctx, x, y, c, &st);
            const uint64_t k = st.nonfinite - before;
            const double on_patch = c[1] * 100.0;
            finite &= isfinite(c[0]) && isfinite(c[1]) && isfinite(c[2]);
            whole &= fabs(on_patch - round(on_patch)) < 1e-3;
            mixed += k > 0 && on_patch > 0.5 && on_patch < 99.5 && (int)(100 - k) % 100 != 0;
        }
    printf("%llu non-finite samples of %llu; %d pixels with some on the patch and some non-finite\n",
           (unsigned long long)st.nonfinite, (unsigned long long)st.samples, mixed);
    CHECK(finite);
    CHECK(whole);
    CHECK(mixed >= 4);
    CHECK(st.nonfinite > 100);
    render_ctx_free(ctx);
    sampler_free(pix);
    scene_file_free(&sf);
    return check_report("test_nonfinite");
}
