/* test_flip: FLIP is 0 for equal images and near 1 for black against white, grows with the error,
   counts only a mask's pixels (filters still see the rest); HDR-FLIP's exposures follow the
   reference's luminance; metrics over a rectangle equal the cropped images'; bad masks are refused. */
#include "image/flip.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/rng.h"
#include "check.h"
#include "image/metrics.h"

/* A w x h image of value v in every channel, plus noise of amplitude amp from seed. */
static struct rgbf grey(int w, int h, float v, double amp, uint64_t seed)
{
    struct rgbf img = {w, h, malloc(sizeof(float) * 3 * (size_t)w * h)};
    struct rng rng;
    rng_seed(&rng, seed, 1);
    for (int i = 0; i < 3 * w * h; i++)
        img.px[i] = (float)(v + amp * (rng_uniform(&rng) - 0.5));
    return img;
}

static double ldr(const struct rgbf *a, const struct rgbf *b, const struct img_mask *m)
{
    struct flip_result r = {-1, -1, 0, 0, 0};
    struct err e;
    CHECK(flip_ldr(a, b, m, NULL, &r, &e) == 0 && r.hdr == 0);
    return r.mean;
}

static void equal_and_extremes(void)
{
    struct rgbf a = grey(24, 20, 0.4f, 0.3, 1), black = grey(24, 20, 0, 0, 1), white = grey(24, 20, 1, 0, 1);
    struct flip_result r;
    struct err e;
    CHECK(ldr(&a, &a, NULL) == 0);
    CHECK(flip_hdr(&a, &a, NULL, NULL, &r, &e) == 0 && r.mean == 0 && r.hdr == 1);
    double bw = ldr(&black, &white, NULL);
    CHECK(bw > 0.9 && bw <= 1.0);
    /* more noise, more visible error */
    struct rgbf n1 = grey(24, 20, 0.4f, 0.05, 9), n2 = grey(24, 20, 0.4f, 0.3, 9),
                flat = grey(24, 20, 0.4f, 0, 9);
    double f1 = ldr(&flat, &n1, NULL), f2 = ldr(&flat, &n2, NULL);
    CHECK(f1 > 0 && f2 > f1 && f2 < 1);
    CHECK(flip_ldr(&a, &white, NULL, NULL, &r, &e) == 0);
    white.w = 12;
    CHECK(flip_ldr(&a, &white, NULL, NULL, &r, &e) == -1 && strstr(e.msg, "sizes differ"));
    white.w = 24;
    n1.px[7] = NAN;
    CHECK(flip_hdr(&flat, &n1, NULL, NULL, &r, &e) == -1 && strstr(e.msg, "non-finite"));
    free(a.px), free(black.px), free(white.px), free(n1.px), free(n2.px), free(flat.px);
}

/* The brightest pixel of the reference reaches 0.85 through the tone mapper at the start exposure,
   the median at the stop exposure: a flat reference gives start == stop and two exposures. */
static void exposures(void)
{
    struct rgbf a = grey(16, 16, 2.0f, 0, 1), b = grey(16, 16, 2.0f, 0.5, 3);
    struct flip_result r;
    struct err e;
    CHECK(flip_hdr(&a, &b, NULL, NULL, &r, &e) == 0);
    double x = 2.0 * exp2(r.start_exposure),
           k[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
    CHECK_NEAR((k[0] * x * x + k[1] * x + k[2]) / (k[3] * x * x + k[4] * x + k[5]), 0.85, 1e-9);
    CHECK_NEAR(r.stop_exposure, r.start_exposure, 1e-12);
    CHECK(r.n_exposures == 2 && r.mean > 0);
    /* one pixel 256 times brighter than the rest: 8 stops between start and stop */
    a.px[0] = a.px[1] = a.px[2] = 512;
    CHECK(flip_hdr(&a, &b, NULL, NULL, &r, &e) == 0);
    CHECK_NEAR(r.stop_exposure - r.start_exposure, 8, 1e-9);
    CHECK(r.n_exposures == 8);
    free(a.px), free(b.px);
}

/* Images that differ only in columns x < 16: over a mask of columns >= 40 (further than any
   filter reaches) FLIP is 0; over the whole image it is not. */
static void masked_flip(void)
{
    struct rgbf a = grey(64, 32, 0.5f, 0.2, 4), b = grey(64, 32, 0.5f, 0.2, 4);
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 16; x++)
            b.px[3 * (y * 64 + x)] = 0.9f;
    struct img_mask m;
    struct err e;
    long rect[4] = {40, 0, 64, 32};
    CHECK(mask_rect(&m, 64, 32, rect, &e) == 0 && m.count == 24 * 32);
    CHECK(ldr(&a, &b, &m) == 0 && ldr(&a, &b, NULL) > 0.05);
    float *map = malloc(sizeof(float) * 64 * 32);
    struct flip_result r;
    CHECK(flip_hdr(&a, &b, &m, map, &r, &e) == 0 && r.mean == 0 && map[0] > 0 && map[63] == 0);
    free(map);
    mask_free(&m);
    free(a.px), free(b.px);
}

/* metrics over a rectangle: exactly the cropped images' figures. */
static void masked_metrics(void)
{
    struct rgbf a = grey(20, 12, 0.5f, 0.8, 5), b = grey(20, 12, 0.5f, 0.8, 6);
    struct rgbf ca = {7, 5, malloc(sizeof(float) * 3 * 35)}, cb = {7, 5, malloc(sizeof(float) * 3 * 35)};
    for (int y = 0; y < 5; y++)
        for (int x = 0; x < 7; x++)
            for (int c = 0; c < 3; c++) {
                ca.px[(y * 7 + x) * 3 + c] = a.px[((y + 4) * 20 + x + 3) * 3 + c];
                cb.px[(y * 7 + x) * 3 + c] = b.px[((y + 4) * 20 + x + 3) * 3 + c];
            }
    struct img_mask m;
    struct metrics whole, masked, cropped;
    struct err e;
    long rect[4] = {3, 4, 10, 9};
    CHECK(mask_rect(&m, 20, 12, rect, &e) == 0 && m.count == 35 && m.x0 == 3 && m.y1 == 9);
    CHECK(metrics_compare_masked(&a, &b, 1, &m, &masked, &e) == 0 &&
          metrics_compare_f(&ca, &cb, 1, &cropped, &e) == 0 && metrics_compare_f(&a, &b, 1, &whole, &e) == 0);
    CHECK(masked.mse == cropped.mse && masked.relmse == cropped.relmse && masked.psnr == cropped.psnr &&
          masked.relmse_robust == cropped.relmse_robust);
    CHECK(masked.mse != whole.mse);
    struct rgbf cr = {0}, ci = {0};
    CHECK(mask_crop_pair(&m, &a, &b, &cr, &ci, &e) == 0 && cr.w == 7 && cr.h == 5 &&
          !memcmp(ci.px, cb.px, sizeof(float) * 3 * 35));
    image_f_free(&cr), image_f_free(&ci);
    mask_free(&m);
    free(a.px), free(b.px), free(ca.px), free(cb.px);
}

static void bad_masks(void)
{
    struct img_mask m;
    struct err e;
    long outside[4] = {0, 0, 21, 5}, empty[4] = {4, 2, 4, 6}, negative[4] = {-1, 0, 3, 3}, r[4];
    CHECK(mask_rect(&m, 20, 12, outside, &e) == -1 && strstr(e.msg, "outside the 20x12 image"));
    CHECK(mask_rect(&m, 20, 12, empty, &e) == -1 && strstr(e.msg, "empty"));
    CHECK(mask_rect(&m, 20, 12, negative, &e) == -1 && strstr(e.msg, "outside"));
    struct rgb8 img = {4, 3, calloc(36, 1)};
    CHECK(mask_from_image(&m, &img, &e) == -1 && strstr(e.msg, "no pixel"));
    img.px[3 * 5] = img.px[3 * 5 + 1] = img.px[3 * 5 + 2] = 255; /* pixel (1, 1) white */
    img.px[3 * 6] = 200;                                         /* (2, 1) red: not white */
    CHECK(mask_from_image(&m, &img, &e) == 0 && m.count == 1 && m.x0 == 1 && m.y0 == 1 && m.x1 == 2 &&
          m.y1 == 2);
    CHECK(mask_check_size(&m, 4, 3, &e) == 0 && mask_check_size(&m, 5, 3, &e) == -1 && strstr(e.msg, "4x3"));
    struct rgbf a = grey(5, 3, 0.5f, 0, 1);
    struct metrics mm;
    CHECK(metrics_compare_masked(&a, &a, 1, &m, &mm, &e) == -1 && strstr(e.msg, "mask"));
    mask_free(&m);
    free(img.px), free(a.px);
    CHECK(mask_parse_rect("1,2,30,40", r) == 0 && r[0] == 1 && r[3] == 40);
    CHECK(mask_parse_rect("1,2,30", r) == -1 && mask_parse_rect("1,2,3,4,5", r) == -1 &&
          mask_parse_rect("a.png", r) == -1 && mask_parse_rect("1, 2,3,4", r) == -1);
}

int main(void)
{
    equal_and_extremes();
    exposures();
    masked_flip();
    masked_metrics();
    bad_masks();
    return check_report("test_flip");
}
