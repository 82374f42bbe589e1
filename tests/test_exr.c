/* test_exr: float images (EXR through OpenEXRCore, PFM): round trips give identical floats, the
   bytes depend only on the image, malformed or oversized input is refused with an error. */
#include <openexr.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "image_fixture.h"
#include "base/fileio.h"
#include "image/exr.h"
#include "image/imgio.h"
#include "image/pfm.h"

/* A w x h float image with values across the range a renderer produces (0, tiny, > 1, huge). */
static struct rgbf fpattern(int w, int h)
{
    struct rgbf img;
    image_f_alloc(&img, w, h, NULL);
    for (size_t i = 0; i < (size_t)w * h * 3; i++) {
        uint32_t x = (uint32_t)i * 2654435761u;
        img.px[i] = (float)(x >> 8) / (float)(1 << 24) * (i % 7 == 0 ? 1000.0f : 1.0f);
    }
    img.px[0] = 0;
    img.px[1] = 1e-30f;
    img.px[2] = 3.4e38f;
    return img;
}

static int same_f(const struct rgbf *a, const struct rgbf *b)
{
    return a->w == b->w && a->h == b->h && a->px && b->px &&
           memcmp(a->px, b->px, (size_t)a->w * a->h * 3 * sizeof(float)) == 0;
}

static void test_exr_round_trip(void)
{
    struct err e = {0};
    struct img_attr attrs[] = {{"job", "cornell-poisson"}, {"sampler", "poisson t=1"}};
    for (int s = 0; s < 3; s++) {
        int w = s == 0 ? 1 : s == 1 ? 37 : 300, h = s == 0 ? 1 : s == 1 ? 23 : 17;
        struct rgbf img = fpattern(w, h), back;
        uint8_t *a = NULL, *b = NULL;
        size_t al = 0, bl = 0;
        CHECK(exr_image_encode(&img, attrs, 2, &a, &al, &e) == 0);
        CHECK(exr_image_encode(&img, attrs, 2, &b, &bl, &e) == 0);
        CHECK(al == bl && al > 0 && !memcmp(a, b, al)); /* the bytes depend on the image only */
        CHECK(exr_image_decode(a, al, "t.exr", &back, &e) == 0);
        CHECK(same_f(&img, &back));
        /* every truncation is refused, never read past */
        int refused = 1;
        for (size_t n = 0; n < al; n += n < 400 ? 1 : 97) {
            struct rgbf t;
            refused &= exr_image_decode(a, n, "t.exr", &t, &e) == -1 && t.px == NULL;
        }
        CHECK(refused);
        free(a);
        free(b);
        image_f_free(&back);
        image_f_free(&img);
    }
}

/* Bytes flipped anywhere: refused or decoded, never a crash (ASan watches). */
static void test_exr_corrupt(void)
{
    struct err e = {0};
    struct rgbf img = fpattern(20, 40), back;
    uint8_t *a;
    size_t al;
    CHECK(exr_image_encode(&img, NULL, 0, &a, &al, &e) == 0);
    for (size_t i = 0; i < al; i += 3) {
        uint8_t keep = a[i];
        a[i] ^= (uint8_t)(0x5a + i);
        if (exr_image_decode(a, al, "c.exr", &back, &e) == 0)
            image_f_free(&back);
        a[i] = keep;
    }
    /* data windows past the limits (box2i after its size: min.x, min.y, max.x, max.y): a side
       over IMAGE_MAX_SIDE (the library's own check, told our limit), and 20000 x 20000 sides
       within it but pixels over IMAGE_MAX_PIXELS (ours) */
    static const char key[] = "dataWindow\0box2i";
    uint8_t *p = NULL;
    for (size_t i = 0; !p && i + sizeof key <= al; i++)
        p = memcmp(a + i, key, sizeof key) ? NULL : a + i;
    CHECK(p != NULL);
    if (p) {
        int32_t big[2] = {40000, 0};
        memcpy(p + sizeof key + 4 + 8, big, 4);
        CHECK(exr_image_decode(a, al, "big.exr", &back, &e) == -1 && has(&e, "too large") &&
              !strcmp(e.file, "big.exr"));
        big[0] = big[1] = 19999;
        memcpy(p + sizeof key + 4 + 8, big, 8);
        CHECK(exr_image_decode(a, al, "big.exr", &back, &e) == -1 && has(&e, "out of range") &&
              back.px == NULL);
    }
    CHECK(exr_image_decode((const uint8_t *)"v/1", 3, "x.exr", &back, &e) == -1 && has(&e, "not an OpenEXR"));
    struct img_attr bad[] = {{"compression", "none"}}; /* a required attribute of another type */
    uint8_t *b;
    size_t bl;
    CHECK(exr_image_encode(&img, bad, 1, &b, &bl, &e) == -1 && b == NULL && has(&e, "compression"));
    free(a);
    image_f_free(&img);
}

static int64_t raw_write(exr_const_context_t c, void *ud, const void *buf, uint64_t sz, uint64_t off,
                         exr_stream_error_func_ptr_t cb)
{
    struct buf *b = ud;
    (void)c;
    (void)cb;
    while (b->n < off + sz) {
        uint8_t z = 0;
        buf_add(b, &z, 1);
    }
    memcpy(b->p + off, buf, sz);
    return (int64_t)sz;
}

/* An EXR made here with OpenEXR directly: `parts` parts, each with channels `names` of type t,
   4 x 3, value v everywhere. */
static struct buf other_exr_parts(const char *const *names, int n, exr_pixel_type_t t, float v, int parts)
{
    static const char *const part_names[] = {"one", "two"};
    struct buf b = {0};
    exr_context_t ctx;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = &b;
    init.write_fn = raw_write;
    int part, spc;
    uint16_t half = 0x3c00; /* 1.0 */
    float fl[12];
    for (int i = 0; i < 12; i++)
        fl[i] = v;
    exr_start_write(&ctx, "o.exr", EXR_WRITE_FILE_DIRECTLY, &init);
    for (int p = 0; p < parts; p++) {
        exr_add_part(ctx, parts > 1 ? part_names[p] : NULL, EXR_STORAGE_SCANLINE, &part);
        exr_initialize_required_attr_simple(ctx, part, 4, 3, EXR_COMPRESSION_PIZ);
        for (int c = 0; c < n; c++)
            exr_add_channel(ctx, part, names[c], t, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    }
    exr_write_header(ctx);
    for (part = 0; part < parts; part++) {
        exr_get_scanlines_per_chunk(ctx, part, &spc);
        exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
        exr_chunk_info_t ci;
        exr_write_scanline_chunk_info(ctx, part, 0, &ci);
        exr_encoding_initialize(ctx, part, &ci, &enc);
        for (int c = 0; c < enc.channel_count; c++) {
            enc.channels[c].encode_from_ptr =
                t == EXR_PIXEL_HALF ? (const uint8_t *)&half : (const uint8_t *)fl;
            enc.channels[c].user_pixel_stride = 0;
            enc.channels[c].user_line_stride = 0;
            enc.channels[c].user_data_type = (uint16_t)t;
            enc.channels[c].user_bytes_per_element = t == EXR_PIXEL_HALF ? 2 : 4;
        }
        exr_encoding_choose_default_routines(ctx, part, &enc);
        exr_encoding_run(ctx, part, &enc);
        exr_encoding_destroy(ctx, &enc);
    }
    exr_finish(&ctx);
    return b;
}

static struct buf other_exr(const char *const *names, int n, exr_pixel_type_t t, float v)
{
    return other_exr_parts(names, n, t, v, 1);
}

/* Issue 27: a multipart file is refused, not read as its first part; a header of more attributes
   than EXR_MAX_ATTRIBUTES is refused before the library's quadratic parse, fewer are read. */
static void test_exr_parts_and_attributes(void)
{
    struct err e = {0};
    struct rgbf back = {0}, img = fpattern(4, 3);
    static const char *const rgb[] = {"B", "G", "R"};
    struct buf b = other_exr_parts(rgb, 3, EXR_PIXEL_FLOAT, 1, 2);
    CHECK(exr_image_decode(b.p, b.n, "m.exr", &back, &e) == -1 && has(&e, "multipart file (2 parts)"));
    free(b.p);
    enum { MANY = 2000 };
    struct img_attr *attrs = calloc(MANY, sizeof *attrs);
    char(*keys)[16] = calloc(MANY, sizeof *keys);
    for (int i = 0; i < MANY; i++) {
        snprintf(keys[i], sizeof keys[i], "k%d", i);
        attrs[i] = (struct img_attr){keys[i], "v"};
    }
    uint8_t *a = NULL;
    size_t al = 0;
    CHECK(exr_image_encode(&img, attrs, MANY, &a, &al, &e) == 0);
    CHECK(exr_image_decode(a, al, "a.exr", &back, &e) == 0 && same_f(&img, &back));
    image_f_free(&back);
    /* EXR_MAX_ATTRIBUTES + 1 more spliced in after the version field */
    struct buf many = {0};
    buf_add(&many, a, 8);
    for (int i = 0; i <= EXR_MAX_ATTRIBUTES; i++) {
        char attr[32];
        int n = snprintf(attr, sizeof attr, "x%d%cstring%c", i, 0, 0);
        static const uint8_t one[5] = {1, 0, 0, 0, 'v'};
        buf_add(&many, attr, (size_t)n);
        buf_add(&many, one, sizeof one);
    }
    buf_add(&many, a + 8, al - 8);
    CHECK(exr_image_decode(many.p, many.n, "many.exr", &back, &e) == -1 && has(&e, "header attributes") &&
          back.px == NULL);
    free(many.p);
    free(a);
    free(attrs);
    free(keys);
    image_f_free(&img);
}

static void test_exr_other_files(void)
{
    struct err e = {0};
    struct rgbf back;
    static const char *const rgba[] = {"A", "B", "G", "R"}, *const y[] = {"Y"};
    struct buf b = other_exr(rgba, 4, EXR_PIXEL_HALF, 1);
    CHECK(exr_image_decode(b.p, b.n, "h.exr", &back, &e) == 0 && back.w == 4 && back.h == 3);
    int ones = back.px != NULL;
    for (int i = 0; back.px && i < 36; i++)
        ones &= back.px[i] == 1.0f;
    CHECK(ones); /* half, PIZ, alpha ignored */
    image_f_free(&back);
    free(b.p);
    b = other_exr(y, 1, EXR_PIXEL_FLOAT, 0.5f);
    CHECK(exr_image_decode(b.p, b.n, "y.exr", &back, &e) == -1 && has(&e, "R, G and B"));
    free(b.p);
    b = other_exr(rgba + 1, 3, EXR_PIXEL_UINT, 0);
    CHECK(exr_image_decode(b.p, b.n, "u.exr", &back, &e) == -1 && has(&e, "half or float"));
    free(b.p);
}

static void test_pfm(void)
{
    struct err e = {0};
    struct rgbf img = fpattern(5, 3), back;
    uint8_t *a;
    size_t al;
    CHECK(pfm_encode(&img, &a, &al, &e) == 0);
    CHECK(al == 12 + 5 * 3 * 12 && !memcmp(a, "PF\n5 3\n-1.0\n", 12));
    float first;
    memcpy(&first, a + 12, 4);
    CHECK(first == img.px[2 * 5 * 3]); /* the bottom row comes first */
    CHECK(pfm_decode(a, al, "t.pfm", &back, &e) == 0 && same_f(&img, &back));
    image_f_free(&back);
    int refused = 1;
    for (size_t n = 0; n < al; n++)
        refused &= pfm_decode(a, n, "t.pfm", &back, &e) == -1 && back.px == NULL;
    CHECK(refused);
    free(a);

    /* big-endian (positive scale) and grey "Pf" */
    uint8_t be[] = "PF\n1 1\n1.0\n\x3f\x80\x00\x00\x40\x00\x00\x00\x00\x00\x00\x00";
    CHECK(pfm_decode(be, sizeof be - 1, "be.pfm", &back, &e) == 0 && back.px[0] == 1.0f &&
          back.px[1] == 2.0f && back.px[2] == 0.0f);
    image_f_free(&back);
    uint8_t grey[] = "Pf 1 1 -1\n\x00\x00\x80\x3f";
    CHECK(pfm_decode(grey, sizeof grey - 1, "g.pfm", &back, &e) == 0 && back.px[0] == 1.0f &&
          back.px[2] == 1.0f);
    image_f_free(&back);
    static const char *const bad[] = {"PF\n0 1\n-1\n",         "PF\n1 -1\n-1\n", "PF\n40000 1\n-1\n",
                                      "PF\n20000 20000\n-1\n", "PF\n1 1\n0\n",   "PF\n1 1\nabc\n",
                                      "PF\n1 1\n-1\n\x01\x02", "PX\n1 1\n-1\n"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        int ok = pfm_decode((const uint8_t *)bad[i], strlen(bad[i]), "bad.pfm", &back, &e) == -1 &&
                 back.px == NULL && !strcmp(e.file, "bad.pfm");
        if (!ok)
            fprintf(stderr, "accepted bad PFM %zu\n", i);
        CHECK(ok);
    }
    uint8_t extra[] = "PF\n1 1\n-1\n000011112222X";
    CHECK(pfm_decode(extra, sizeof extra - 1, "x.pfm", &back, &e) == -1 && has(&e, "after the raster"));
    /* issue 27: the scale's magnitude multiplies the values (as pbrt reads them); a header with
       CR LF line ends is read (it was "1 bytes after the raster"), and a lone CR ends the header
       when the raster then starts with a 0x0a byte (its first value 0x3f80000a, just above 1). */
    static const struct {
        const char *bytes;
        size_t len;
        float want[3];
    } read[] = {
#define PFM_CASE(s, r, g, b)                                                                                 \
    {                                                                                                        \
        s, sizeof s - 1,                                                                                     \
        {                                                                                                    \
            r, g, b                                                                                          \
        }                                                                                                    \
    }
        PFM_CASE("PF\n1 1\n-4.0\n\x00\x00\x80\x3f\x00\x00\x00\x40\x00\x00\x00\x3f", 4, 8, 2),
        PFM_CASE("PF\r\n1 1\r\n-1.0\r\n\x00\x00\x80\x3f\x00\x00\x00\x40\x00\x00\x00\x3f", 1, 2, 0.5f),
        PFM_CASE("PF\n1 1\n-1.0\r\n\x00\x80\x3f\x00\x00\x00\x40\x00\x00\x00\x3f", 1.0f + 0x0a / 8388608.0f, 2,
                 0.5f),
#undef PFM_CASE
    };
    for (size_t i = 0; i < sizeof read / sizeof *read; i++) {
        int ok = pfm_decode((const uint8_t *)read[i].bytes, read[i].len, "r.pfm", &back, &e) == 0;
        for (int c = 0; ok && c < 3; c++)
            ok = back.px[c] == read[i].want[c];
        if (!ok)
            fprintf(stderr, "PFM %zu read wrong\n", i);
        CHECK(ok);
        image_f_free(&back);
    }
    image_f_free(&img);
}

/* imgio: the four formats by their magic bytes, with the domain they hold. */
static void test_imgio(void)
{
    char dir[] = "/tmp/test_exr.XXXXXX", path[64];
    struct err e = {0};
    CHECK(mkdtemp(dir) != NULL);
    struct rgbf img = fpattern(9, 7), back;
    struct img_attr attrs[] = {{"job", "t"}};
    enum img_domain d = IMG_DISPLAY8;
    snprintf(path, sizeof path, "%s/a.exr", dir);
    CHECK(imgio_write_f(path, &img, IMG_EXR, attrs, 1, &e) == 0);
    CHECK(imgio_read_f(path, &back, &d, &e) == 0 && d == IMG_LINEAR && same_f(&img, &back));
    image_f_free(&back);
    unlink(path);
    snprintf(path, sizeof path, "%s/a.pfm", dir);
    d = IMG_DISPLAY8;
    CHECK(imgio_write_f(path, &img, IMG_PFM, NULL, 0, &e) == 0);
    CHECK(imgio_read_f(path, &back, &d, &e) == 0 && d == IMG_LINEAR && same_f(&img, &back));
    image_f_free(&back);
    unlink(path);
    struct rgb8 p8 = pattern(4, 2);
    snprintf(path, sizeof path, "%s/a.png", dir);
    CHECK(imgio_write(path, &p8, IMG_PNG, &e) == 0);
    CHECK(imgio_read_f(path, &back, &d, &e) == 0 && d == IMG_DISPLAY8 && back.w == 4);
    CHECK(back.px && back.px[5] == (float)(p8.px[5] / 255.0));
    image_f_free(&back);
    unlink(path);
    snprintf(path, sizeof path, "%s/a.txt", dir);
    CHECK(fileio_write_atomic(path, "hello", 5, &e) == 0);
    CHECK(imgio_read_f(path, &back, &d, &e) == -1 && has(&e, "EXR, PFM, PNG or PPM") && back.px == NULL);
    unlink(path);
    CHECK(imgio_write_f(path, &img, IMG_PNG, NULL, 0, &e) == -1);
    image_free(&p8);
    image_f_free(&img);
    rmdir(dir);
}

/* Issue 27: a chunk whose deflate output is exactly as long as its raw bytes was written so that
   readers took it for raw (OpenEXRCore 3.1.5). Images of nearly incompressible bytes (a render's
   noisy mantissas) meet that case a few times in 300 at 48x40; each must read back bit-exact. */
static void test_exr_zip_equal_size_chunks(void)
{
    struct err e = {0};
    uint64_t s = 1;
    int bad = 0;
    for (int k = 0; k < 300; k++) {
        struct rgbf img, back = {0};
        image_f_alloc(&img, 48, 40, NULL);
        unsigned keep = 240 + (unsigned)k % 16; /* of 256: the share of random bytes */
        unsigned char *p = (unsigned char *)img.px;
        for (size_t i = 0; i < (size_t)48 * 40 * 3 * sizeof(float); i++) {
            s = s * 6364136223846793005ull + 1442695040888963407ull;
            unsigned r = (unsigned)(s >> 33);
            p[i] = i % 4 == 3 ? 0x3f : (r & 255) < keep ? (unsigned char)(r >> 8) : 0;
        }
        uint8_t *a = NULL;
        size_t al = 0;
        if (exr_image_encode(&img, NULL, 0, &a, &al, &e) < 0 ||
            exr_image_decode(a, al, "z.exr", &back, &e) < 0)
            bad++;
        else
            bad += !same_f(&img, &back);
        free(a);
        image_f_free(&back);
        image_f_free(&img);
    }
    CHECK(bad == 0);
}

int main(void)
{
    test_exr_round_trip();
    test_exr_zip_equal_size_chunks();
    test_exr_parts_and_attributes();
    test_exr_corrupt();
    test_exr_other_files();
    test_pfm();
    test_imgio();
    return check_report("test_exr");
}
