/* test_errspec: error_lowfreq is about 1 for white error, far above 1 for a smooth error, near 0 for
   an error that alternates pixel to pixel; NaN where the band is empty; sizes must agree. */
#include "image/errspec.h"

#include <math.h>
#include <stdlib.h>

#include "base/rng.h"
#include "check.h"

/* ref all 0.5, img = ref + the error f(x, y) in every channel. */
static double lowfreq_of(int w, int h, double (*f)(int, int, struct rng *), uint64_t seed)
{
    struct rgbf ref = {w, h, malloc(sizeof(float) * 3 * w * h)},
                img = {w, h, malloc(sizeof(float) * 3 * w * h)};
    struct rng rng;
    rng_seed(&rng, seed, 1);
    for (int i = 0; i < w * h; i++) {
        const double d = f(i % w, i / w, &rng);
        for (int c = 0; c < 3; c++) {
            ref.px[3 * i + c] = 0.5f;
            img.px[3 * i + c] = (float)(0.5 + d);
        }
    }
    struct err e;
    double v = -1;
    CHECK(errspec_lowfreq(&ref, &img, &v, &e) == 0);
    free(ref.px);
    free(img.px);
    return v;
}

static double white(int x, int y, struct rng *r)
{
    (void)x, (void)y;
    return rng_uniform(r) - 0.5;
}

static double smooth(int x, int y, struct rng *r)
{
    return 0.1 * sin(2 * M_PI * x / 64.0) + 0.01 * cos(2 * M_PI * y / 64.0) + 0.01 * (rng_uniform(r) - 0.5);
}

static double alternating(int x, int y, struct rng *r)
{
    return ((x + y) & 1 ? 0.1 : -0.1) + 0.001 * (rng_uniform(r) - 0.5);
}

int main(void)
{
    double sum = 0;
    for (uint64_t s = 0; s < 8; s++)
        sum += lowfreq_of(64, 48, white, s) / 8;
    printf("error_lowfreq: white %.3f, smooth %.1f, alternating %.4f\n", sum, lowfreq_of(64, 64, smooth, 1),
           lowfreq_of(64, 64, alternating, 1));
    CHECK_NEAR(sum, 1.0, 0.25);
    CHECK(lowfreq_of(64, 64, smooth, 1) > 10);
    CHECK(lowfreq_of(64, 64, alternating, 1) < 0.01);
    CHECK(lowfreq_of(300, 200, white, 3) > 0.5); /* cropped to 128 x 128 */
    CHECK(isnan(lowfreq_of(8, 8, white, 1)));    /* no frequency within 1/8 Nyquist */
    struct rgbf a = {4, 4, calloc(48, sizeof(float))}, b = {4, 3, calloc(36, sizeof(float))};
    struct err e;
    double v;
    CHECK(errspec_lowfreq(&a, &b, &v, &e) == -1);
    free(a.px);
    free(b.px);
    return check_report("test_errspec");
}
