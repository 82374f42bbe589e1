/* test_metrics: MSE and relMSE worked out by hand on a small pair, the robust variant's trimming
   of the largest per-pixel terms, blocks, and refusals. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "image/metrics.h"

static void set_px(struct rgbf *img, int i, float r, float g, float b)
{
    img->px[3 * i] = r;
    img->px[3 * i + 1] = g;
    img->px[3 * i + 2] = b;
}

static void test_by_hand(void)
{
    struct rgbf ref, img;
    struct metrics m;
    struct err e = {0};
    image_f_alloc(&ref, 2, 1, &e);
    image_f_alloc(&img, 2, 1, &e);
    set_px(&ref, 0, 0, 0.1f, 1);
    set_px(&ref, 1, 0.5f, 0.5f, 0.5f);
    set_px(&img, 0, 0.1f, 0.1f, 1.5f);
    set_px(&img, 1, 0.5f, 0.7f, 0.4f);
    CHECK(metrics_compare_f(&ref, &img, 1, &m, &e) == 0);
    /* differences 0.1, 0, 0.5, 0, 0.2, -0.1; relative terms d^2 / (r^2 + 0.01):
       0.01/0.01 = 1, 0, 0.25/1.01, 0, 0.04/0.26, 0.01/0.26 */
    double rel = (1 + 0.25 / 1.01 + 0.04 / 0.26 + 0.01 / 0.26) / 6;
    CHECK_NEAR(m.mse, 0.31 / 6, 1e-7);
    CHECK_NEAR(m.rmse, sqrt(0.31 / 6), 1e-7);
    CHECK_NEAR(m.relmse, rel, 1e-6);
    CHECK_NEAR(m.relmse, 0.2399720741, 1e-6);
    CHECK(m.relmse_robust == m.relmse); /* 2 pixels: nothing to leave out */
    CHECK_NEAR(m.psnr, 10 * log10(6 / 0.31), 1e-5);
    CHECK(metrics_compare_f(&ref, &ref, 1, &m, &e) == 0 && m.mse == 0 && m.relmse == 0 && isinf(m.psnr));
    /* one 2x2 block: the tile means, ref (0.25, 0.3, 0.75) against (0.3, 0.4, 0.95) */
    CHECK(metrics_compare_f(&ref, &img, 2, &m, &e) == 0);
    CHECK_NEAR(m.mse, (0.0025 + 0.01 + 0.04) / 3, 1e-7);
    CHECK_NEAR(m.relmse, (0.0025 / 0.0725 + 0.01 / 0.1 + 0.04 / 0.5725) / 3, 1e-6);
    image_f_free(&ref);
    image_f_free(&img);
}

static void test_robust(void)
{
    struct rgbf ref, img;
    struct metrics m;
    struct err e = {0};
    int w = 50, h = 41; /* 2050 pixels: the 2 largest terms are left out */
    image_f_alloc(&ref, w, h, &e);
    image_f_alloc(&img, w, h, &e);
    for (int i = 0; i < w * h; i++) {
        set_px(&ref, i, 0.5f, 0.5f, 0.5f);
        set_px(&img, i, 0.5f, 0.5f, 0.5f);
    }
    img.px[3 * 7] = 100.5f;       /* a firefly: term (100^2 / 0.26) / 3 */
    img.px[3 * 1500 + 2] = 50.5f; /* another: (50^2 / 0.26) / 3 */
    CHECK(metrics_compare_f(&ref, &img, 1, &m, &e) == 0);
    CHECK_NEAR(m.relmse, (1e4 + 2500) / 0.26 / (3.0 * w * h), 1e-6);
    CHECK(m.relmse_robust == 0);
    img.px[3 * 900 + 1] = 1.5f; /* a third, smaller one stays in */
    CHECK(metrics_compare_f(&ref, &img, 1, &m, &e) == 0);
    CHECK_NEAR(m.relmse_robust, 1 / 0.26 / 3 / (w * h - 2), 1e-9);
    CHECK_NEAR(m.relmse, (1e4 + 2500 + 1) / 0.26 / (3.0 * w * h), 1e-6);
    /* ties and order do not matter: many equal terms, the largest anywhere */
    for (int i = 0; i < w * h; i++)
        set_px(&img, i, i % 3 ? 0.6f : 0.7f, 0.5f, 0.5f);
    img.px[0] = 9;
    img.px[3 * (w * h - 1)] = 8;
    CHECK(metrics_compare_f(&ref, &img, 1, &m, &e) == 0);
    double d6 = 0.6f - 0.5f, d7 = 0.7f - 0.5f, sum = 0;
    for (int i = 1; i < w * h - 1; i++)
        sum += (i % 3 ? d6 * d6 : d7 * d7) / 0.26 / 3;
    CHECK_NEAR(m.relmse_robust, sum / (w * h - 2), 1e-9);
    image_f_free(&ref);
    image_f_free(&img);
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The trimmed mean against a full sort, on pseudo-random images of several sizes (ties included). */
static void test_robust_random(void)
{
    struct err e = {0};
    int ok = 1;
    for (int s = 0; s < 6; s++) {
        int w = 40 + 37 * s, h = 25 + 11 * s, n = w * h;
        struct rgbf ref, img;
        struct metrics m;
        image_f_alloc(&ref, w, h, &e);
        image_f_alloc(&img, w, h, &e);
        uint32_t x = 12345u + (uint32_t)s;
        for (int i = 0; i < 3 * n; i++) {
            x = x * 1664525u + 1013904223u;
            ref.px[i] = (float)(x >> 28) / 4;
            img.px[i] = ref.px[i] + (float)((x >> 20) & (s % 2 ? 3 : 255)) / 64;
        }
        double *t = malloc(sizeof *t * (size_t)n);
        for (int i = 0; i < n; i++) {
            t[i] = 0;
            for (int c = 0; c < 3; c++) {
                double a = ref.px[3 * i + c], d = img.px[3 * i + c] - a;
                t[i] += d * d / (a * a + 0.01);
            }
            t[i] /= 3;
        }
        qsort(t, (size_t)n, sizeof *t, cmp_d);
        int kept = n - n / 1000;
        double sum = 0;
        for (int i = 0; i < kept; i++)
            sum += t[i];
        ok &= metrics_compare_f(&ref, &img, 1, &m, &e) == 0 &&
              fabs(m.relmse_robust - sum / kept) <= 1e-12 * (sum / kept);
        free(t);
        image_f_free(&ref);
        image_f_free(&img);
    }
    CHECK(ok);
}

static void test_refusals(void)
{
    struct rgbf a, b;
    struct metrics m;
    struct err e = {0};
    image_f_alloc(&a, 3, 2, &e);
    image_f_alloc(&b, 2, 3, &e);
    CHECK(metrics_compare_f(&a, &b, 1, &m, &e) == -1 && strstr(e.msg, "sizes differ"));
    image_f_free(&b);
    image_f_alloc(&b, 3, 2, &e);
    CHECK(metrics_compare_f(&a, &b, 0, &m, &e) == -1 && strstr(e.msg, "block"));
    b.px[4] = NAN;
    CHECK(metrics_compare_f(&a, &b, 1, &m, &e) == -1 && strstr(e.msg, "non-finite value at pixel (1, 0)"));
    image_f_free(&a);
    image_f_free(&b);
    /* the display metrics: 8-bit values over 255 */
    struct rgb8 r8, i8;
    image_alloc(&r8, 1, 1, &e);
    image_alloc(&i8, 1, 1, &e);
    i8.px[0] = 255;
    CHECK(metrics_display_compare(&r8, &i8, &m, &e) == 0);
    CHECK_NEAR(m.mse, 1.0 / 3, 1e-7);
    CHECK_NEAR(m.relmse, 1 / 0.01 / 3, 1e-4);
    image_free(&r8);
    image_free(&i8);
}

int main(void)
{
    test_by_hand();
    test_robust();
    test_robust_random();
    test_refusals();
    return check_report("test_metrics");
}
