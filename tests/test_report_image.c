/* test_report_image: the compare report's image analysis: the worst window finds where images
   differ from the reference, crops zoom the right pixels, error maps' gain and clamping. */
#include <string.h>

#include "check.h"
#include "study/report_image.h"

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

static void test_crop_zoom(void)
{
    struct rgb8 src, out;
    struct err e = {0};
    flat(&src, 10, 10, 0);
    set_px(&src, 5, 6, 77);
    CHECK(report_image_crop_zoom(&src, 4, 6, 3, &out, &e) == 0);
    CHECK(out.w == 3 * REPORT_IMAGE_CROP_ZOOM && out.h == 3 * REPORT_IMAGE_CROP_ZOOM);
    int lit = 0;
    for (int y = 0; y < out.h; y++)
        for (int x = 0; x < out.w; x++) {
            int v = out.px[((size_t)y * out.w + x) * 3 + 1];
            int want = x / REPORT_IMAGE_CROP_ZOOM == 1 && y / REPORT_IMAGE_CROP_ZOOM == 0 ? 77 : 0;
            lit += v == 77;
            CHECK(v == want);
        }
    CHECK(lit == REPORT_IMAGE_CROP_ZOOM * REPORT_IMAGE_CROP_ZOOM);
    image_free(&out);
    image_free(&src);
}

static void test_error_maps(void)
{
    struct rgb8 ref, img, map;
    struct err e = {0};
    flat(&ref, 10, 10, 50);
    CHECK(report_image_error_gain(&ref, &ref, 1) == REPORT_IMAGE_GAIN_MAX); /* no error at all */
    flat(&img, 10, 10, 55);
    CHECK(report_image_error_gain(&ref, &img, 1) == 51); /* every difference 5: 255 / 5 */
    set_px(&img, 0, 0, 250);                             /* 1% of the pixels far off: over the 99th */
    CHECK(report_image_error_gain(&ref, &img, 1) == 51);
    set_px(&img, 1, 0, 250); /* 2%: now the 99th percentile is 200 */
    CHECK(report_image_error_gain(&ref, &img, 1) == 1);
    set_px(&img, 2, 0, 47);
    CHECK(report_image_error_map(&ref, &img, 51, &map, &e) == 0);
    CHECK(map.px[0] == 255);        /* 200 x 51, clamped */
    CHECK(map.px[2 * 3] == 3 * 51); /* |47 - 50| x 51: below the reference counts too */
    CHECK(map.px[5 * 3] == 255);    /* 5 x 51 */
    image_free(&map);
    image_free(&img);
    image_free(&ref);
}

int main(void)
{
    test_worst_window();
    test_crop_zoom();
    test_error_maps();
    return check_report("test_report_image");
}
