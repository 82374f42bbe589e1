/* test_ppm: the PPM codec and the image buffer (rgb8 and the float-to-8-bit conversion). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "image/image.h"
#include "image_fixture.h"
#include "image/ppm.h"

static void test_float_to_rgb8(void)
{
    const float in[9] = {0.0f, 1.0f, 0.25f, NAN, -1.0f, 4.0f, INFINITY, 0.5f, 0.0f};
    uint8_t out[9] = {0};
    out[8] = 77;
    image_float_to_rgb8(in, 1, 1, out);
    CHECK(out[0] == 0 && out[1] == 255 && out[2] == 128);
    image_float_to_rgb8(in + 3, 1, 1, out);
    CHECK(out[0] == 0);                         /* NaN */
    CHECK(out[1] == 0);                         /* negative */
    CHECK(out[2] == 255);                       /* above 1 */
    image_float_to_rgb8(in + 6, 1, 1, out + 6); /* writes out[6..8] only */
    CHECK(out[6] == 255 && out[7] == 181 && out[8] == 0);
    image_float_to_rgb8(in, 0, 5, out); /* empty image writes nothing */
    CHECK(out[0] == 0 && out[1] == 0 && out[2] == 255);
}

static void test_rgb8_alloc(void)
{
    struct rgb8 img = {0};
    struct err e = {0};
    image_free(&img); /* a zeroed struct is fine */
    image_free(NULL);
    CHECK(image_alloc(&img, 0, 4, &e) == -1 && img.px == NULL && has(&e, "out of range"));
    CHECK(image_alloc(&img, 4, -1, &e) == -1);
    CHECK(image_alloc(&img, IMAGE_MAX_SIDE + 1, 1, &e) == -1);
    CHECK(image_alloc(&img, 3, 2, &e) == 0 && img.w == 3 && img.h == 2 && img.px);
    int zero = 1;
    for (int i = 0; img.px && i < 18; i++)
        zero &= img.px[i] == 0;
    CHECK(zero);
    image_free(&img);
    CHECK(img.px == NULL && img.w == 0);
    image_free(&img); /* twice is harmless */
}

static int ppm_str(const char *s, size_t n, struct rgb8 *out, struct err *e)
{
    memset(e, 0, sizeof *e);
    int rc = ppm_decode((const uint8_t *)s, n, "t.ppm", out, e);
    if (rc != 0 && (out->px || out->w))
        rc = -2;
    return rc;
}

static void test_ppm_round_trip(void)
{
    struct rgb8 img = pattern(5, 3), out;
    struct err e = {0};
    uint8_t *ppm;
    size_t n;
    CHECK(ppm_encode(&img, &ppm, &n, &e) == 0);
    CHECK(n == 11 + 45 && !memcmp(ppm, "P6\n5 3\n255\n", 11));
    CHECK(ppm_decode(ppm, n, "a.ppm", &out, &e) == 0 && same_image(&img, &out));
    image_free(&out);
    int prefix_fail = 0;
    for (size_t k = 0; k < n; k++)
        prefix_fail += ppm_decode(ppm, k, "a.ppm", &out, &e) == -1 && out.px == NULL;
    CHECK(prefix_fail == (int)n);
    CHECK(has(&e, "truncated PPM"));
    free(ppm);

    /* the same pixels as P3, with comments and odd spacing */
    struct buf b = {0};
    buf_add(&b, "P3 # plain\n5\t3\n# max\n255", 24);
    size_t last_start = 0;
    for (int i = 0; i < 45; i++) {
        char num[16];
        last_start = b.n + 1; /* where the last sample's digits begin, after its newline */
        int len = snprintf(num, sizeof num, i % 4 ? " %d" : "\n%d #c\n", img.px[i]);
        buf_add(&b, num, (size_t)len);
    }
    CHECK(ppm_str((const char *)b.p, b.n, &out, &e) == 0 && same_image(&img, &out));
    image_free(&out);
    prefix_fail = 0;
    for (size_t k = 0; k <= last_start; k++) /* cutting inside the last number still parses */
        prefix_fail += ppm_str((const char *)b.p, k, &out, &e) == -1;
    CHECK(prefix_fail == (int)last_start + 1);
    free(b.p);
    image_free(&img);
}

static void test_ppm_maxval(void)
{
    struct rgb8 out;
    struct err e;
    const char wide[] = "P6\n# sixteen bit\n2 1\n65535\n\xff\xff\x80\x00\x00\x00"
                        "\x00\x01\x7f\xff\x80\x80";
    CHECK(ppm_str(wide, sizeof wide - 1, &out, &e) == 0);
    CHECK(out.px && out.px[0] == 255 && out.px[1] == 128 && out.px[2] == 0);
    CHECK(out.px && out.px[3] == 0 && out.px[4] == 127 && out.px[5] == 128);
    image_free(&out);
    const char p3[] = "P3 2 1 65535 65535 0 32768 1 257 65534";
    CHECK(ppm_str(p3, sizeof p3 - 1, &out, &e) == 0);
    CHECK(out.px && !memcmp(out.px, "\xff\x00\x80\x00\x01\xff", 6));
    image_free(&out);
    const char one[] = "P3\n2 1\n1\n1 0 1\n0 1 0\n";
    CHECK(ppm_str(one, sizeof one - 1, &out, &e) == 0);
    CHECK(out.px && !memcmp(out.px, "\xff\x00\xff\x00\xff\x00", 6));
    image_free(&out);
    const char thousand[] = "P3 1 1 1000 500 2 998";
    CHECK(ppm_str(thousand, sizeof thousand - 1, &out, &e) == 0);
    CHECK(out.px && out.px[0] == 128 && out.px[1] == 1 && out.px[2] == 254);
    image_free(&out);
    const char small[] = "P6 1 1 100\n\x64\x00\x65";
    CHECK(ppm_str(small, sizeof small - 1, &out, &e) == -1 && has(&e, "exceeds maxval 100"));
}

static void test_ppm_garbage(void)
{
    const char *bad[] = {
        "",
        "P",
        "P3",
        "P6 ",
        "P5 1 1 255\n\x01",
        "P7 1 1 255\n",
        "Q6 1 1 255\n",
        "P61 1 255\n",
        "P6 0 1 255\n",
        "P6 1 0 255\n",
        "P6 1 1 0\n",
        "P6 1 1 65536\n",
        "P6 -1 1 255\n",
        "P6 99999999999999999999999999 1 255\n",
        "P6 1x 1 255\nabc",
        "P6 40000 1 255\n",
        "P6 32768 32768 255\n",
        "P6 1 1 255#\nabc",
        "P6 1 1 255",
        "P3 1 1 255 1 2 256",
        "P3 1 1 255 1 2 -3",
        "P3 1 1 255 1 2",
        "P3 1 1 255 1 2 3x",
        "P6 1 1 255\n\x01\x02",
        "P3 1 1 255 1 2 99999999999999999999999999999",
    };
    int failed = 0;
    struct rgb8 out;
    struct err e;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        int rc = ppm_str(bad[i], strlen(bad[i]), &out, &e);
        failed += rc == -1 && e.msg[0] && !strcmp(e.file, "t.ppm");
        if (rc != -1)
            fprintf(stderr, "  accepted or leaked: \"%s\"\n", bad[i]);
        image_free(&out);
    }
    CHECK(failed == (int)(sizeof bad / sizeof bad[0]));
    const char late[] = "P3\n1 1\n255\n0 0 300\n";
    CHECK(ppm_str(late, sizeof late - 1, &out, &e) == -1 && e.line == 4 && e.col > 1);
    const char p5[] = "P5 1 1 255\n\x01";
    CHECK(ppm_str(p5, sizeof p5 - 1, &out, &e) == -1 && has(&e, "P5"));
    const char trailing[] = "P6 1 1 255\n\x01\x02\x03P6 1 1 255\n";
    CHECK(ppm_str(trailing, sizeof trailing - 1, &out, &e) == 0 && out.px[2] == 3);
    image_free(&out);
}

int main(void)
{
    test_float_to_rgb8();
    test_rgb8_alloc();
    test_ppm_round_trip();
    test_ppm_maxval();
    test_ppm_garbage();
    return check_report("test_ppm");
}
