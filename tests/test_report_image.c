/* test_report_image: the compare report's image analysis: the zoom is an integer of at least 2,
   the worst window finds where images differ from the reference, crops take the right pixels,
   the colour bar is the error maps' own scale. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "image/errmap.h"
#include "study/present/report_image.h"

/* An image of w x h pixels, every channel v. */
static void flat(struct rgb8 *img, int w, int h, uint8_t v)
{
    struct err e = {0};
    CHECK(image_alloc(img, w, h, &e) == 0);
    memset(img->px, v, (size_t)w * h * 3);
}

static void set_px(struct rgb8 *img, int x, int y, uint8_t v)
{
    memset(&img->px[((size_t)y * img->w + x) * 3], v, 3);
}

static void test_worst_window(void)
{
    struct rgb8 ref, imgs[2];
    flat(&ref, 40, 32, 100);
    flat(&imgs[0], 40, 32, 100);
    flat(&imgs[1], 40, 32, 100);
    for (int y = 20; y < 24; y++) /* a 4x4 blob off in the second image only */
        for (int x = 26; x < 30; x++)
            set_px(&imgs[1], x, y, 200);
    set_px(&imgs[0], 3, 3, 101); /* and a faint difference elsewhere */
    int bx = -1, by = -1;
    report_image_worst_window(&ref, imgs, 2, 8, &bx, &by);
    CHECK(bx >= 22 && bx <= 26 && bx % 2 == 0); /* the window (step 2) holds the whole blob */
    CHECK(by >= 16 && by <= 20 && by % 2 == 0);
    /* equal images: some window on the grid, inside the image */
    report_image_worst_window(&ref, &ref, 1, 8, &bx, &by);
    CHECK(bx >= 0 && by >= 0 && bx + 8 <= 40 && by + 8 <= 32);
    for (int i = 0; i < 2; i++)
        image_free(&imgs[i]);
    image_free(&ref);
}

static void test_zoom(void)
{
    CHECK(report_image_zoom(64, 256) == 4);  /* exactly 256 */
    CHECK(report_image_zoom(100, 256) == 3); /* the smallest reaching 256: 300 */
    CHECK(report_image_zoom(300, 256) == 2); /* never below 2, however large */
    CHECK(report_image_zoom(4000, 256) == 2);
    CHECK(report_image_zoom(12, 160) == 14); /* a crop: 168 */
    CHECK(report_image_zoom(1, 256) == 256);
}

static void test_crop(void)
{
    struct rgb8 src, out;
    struct err e = {0};
    flat(&src, 10, 10, 0);
    set_px(&src, 5, 6, 77);
    CHECK(report_image_crop(&src, 4, 6, 3, &out, &e) == 0);
    CHECK(out.w == 3 && out.h == 3);
    for (int y = 0; y < out.h; y++)
        for (int x = 0; x < out.w; x++)
            CHECK(out.px[((size_t)y * out.w + x) * 3 + 1] == (x == 1 && y == 0 ? 77 : 0));
    image_free(&out);
    image_free(&src);
}

/* The colour bar is errmap_make's own colouring: black-purple at the low end, pale yellow at the
   high end, brighter all the way; a map pixel of term 10^L matches the bar's column for L. */
static void test_errmap_bar(void)
{
    struct rgb8 bar, map;
    struct rgbf ref, img;
    struct err e = {0};
    CHECK(report_image_errmap_bar(60, &bar, &e) == 0);
    CHECK(bar.w == 60 && bar.h == 1);
    CHECK(bar.px[0] < 10 && bar.px[2] < 20); /* near {0, 0, 4} */
    CHECK(bar.px[59 * 3] > 245 && bar.px[59 * 3 + 1] > 245 &&
          bar.px[59 * 3 + 2] > 150); /* near {252, 255, 164} */
    int rising = 1;
    for (int i = 1; i < 60; i++) {
        int a = bar.px[(i - 1) * 3] + bar.px[(i - 1) * 3 + 1] + bar.px[(i - 1) * 3 + 2];
        int b = bar.px[i * 3] + bar.px[i * 3 + 1] + bar.px[i * 3 + 2];
        rising &= b >= a;
    }
    CHECK(rising);
    /* column 29 is L = -4 + 6 x 29.5 / 60 = -1.05: a grey 0.1 against a reference of 0.3 has a term
       0.01 / (0.09 + 0.01) = 0.1 (L = -1), within a column of it */
    CHECK(image_f_alloc(&ref, 1, 1, &e) == 0 && image_f_alloc(&img, 1, 1, &e) == 0);
    for (int c = 0; c < 3; c++)
        ref.px[c] = 0.3f, img.px[c] = 0.4f;
    CHECK(errmap_make(&ref, &img, &map, &e) == 0);
    for (int c = 0; c < 3; c++)
        CHECK(abs((int)map.px[c] - (int)bar.px[29 * 3 + c]) <= 6);
    image_free(&map);
    image_f_free(&ref);
    image_f_free(&img);
    image_free(&bar);
}

int main(void)
{
    test_worst_window();
    test_zoom();
    test_crop();
    test_errmap_bar();
    return check_report("test_report_image");
}
