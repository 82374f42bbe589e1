/* diff: `worker diff`: read two images of any supported format, measure B against A in one
   domain, print the figures (lines or JSON), optionally draw the error map. */
#include "diff.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fileio.h"
#include "cli.h"
#include "image/errmap.h"
#include "image/flip.h"
#include "image/imgio.h"
#include "image/metrics.h"
#include "image/png.h"

/* A finite decimal number (not nan, inf or hex, which strtod takes too). 0, or -1. */
static int parse_number(const char *s, double *out)
{
    char *end;
    *out = strtod(s, &end);
    return *s && !*end && isfinite(*out) && strspn(s, "0123456789+-.eE") == strlen(s) ? 0 : -1;
}

/* A float image's values as 8-bit display values v / 255 (what its PNG would hold), in place. */
static int to_display(struct rgbf *img, struct err *e)
{
    struct rgb8 b = {0};
    struct rgbf d = {0};
    if (image_alloc(&b, img->w, img->h, e) < 0)
        return -1;
    image_float_to_rgb8(img->px, img->w, img->h, b.px);
    int rc = image_f_from_rgb8(&b, &d, e);
    image_free(&b);
    if (rc == 0) {
        image_f_free(img);
        *img = d;
    }
    return rc;
}

static void print_number(const char *key, double v, const char *after)
{
    if (isfinite(v))
        printf("\"%s\": %.10g%s", key, v, after);
    else
        printf("\"%s\": null%s", key, after);
}

static int write_map(const char *path, const struct rgbf *ref, const struct rgbf *img, struct err *e)
{
    struct rgb8 map = {0};
    uint8_t *png = NULL;
    size_t len;
    const struct img_attr text[] = {{ERRMAP_TEXT_KEY, errmap_scale_text()}};
    int rc = errmap_make(ref, img, &map, e) < 0 || png_encode_text(&map, text, 1, &png, &len, e) < 0 ||
                     fileio_write_atomic(path, png, len, e) < 0
                 ? -1
                 : 0;
    if (rc < 0 && !e->file[0])
        snprintf(e->file, sizeof e->file, "%s", path);
    free(png);
    image_free(&map);
    return rc;
}

/* --mask's value: "x0,y0,x1,y1" or an image file (white = counted), for w x h images. 0 or -1. */
static int load_mask(const char *arg, int w, int h, struct img_mask *mask, struct err *e)
{
    long rect[4];
    struct rgb8 img = {0};
    int is_rect = mask_parse_rect(arg, rect) == 0, numbers = strspn(arg, "0123456789,-+ ") == strlen(arg);
    int rc = is_rect   ? mask_rect(mask, w, h, rect, e)
             : numbers ? err_set(e, NULL, 0, 0, "must be x0,y0,x1,y1 (four whole numbers) or an image file")
             : imgio_read(arg, &img, e) < 0                                             ? -1
             : mask_from_image(mask, &img, e) < 0 || mask_check_size(mask, w, h, e) < 0 ? -1
                                                                                        : 0;
    image_free(&img);
    if (rc < 0) {
        mask_free(mask);
        char what[600];
        snprintf(what, sizeof what, "--mask %s", arg);
        err_prefix(e, what);
        snprintf(e->file, sizeof e->file, "worker diff");
    }
    return rc;
}

/* What measure found. */
struct diff_figures {
    struct metrics m;
    struct flip_result flip;
    enum img_domain domain;
    size_t mask_pixels; /* 0: no mask */
};

/* Measure files[1] against files[0] (over mask_arg's pixels when given); fill f, write the map
   (when map_path). 0 or -1. */
static int measure(const char *const files[2], int block, const char *map_path, const char *mask_arg,
                   struct diff_figures *f, struct err *e)
{
    struct img_mask mask = {0};
    enum img_domain *domain = &f->domain;
    struct rgbf img[2] = {{0}, {0}};
    enum img_domain d[2];
    int rc = -1;
    for (int i = 0; i < 2; i++)
        if (imgio_read_f(files[i], &img[i], &d[i], e) < 0)
            goto done;
    *domain = d[0] == IMG_LINEAR && d[1] == IMG_LINEAR ? IMG_LINEAR : IMG_DISPLAY8;
    for (int i = 0; i < 2; i++)
        if (d[i] == IMG_LINEAR && *domain == IMG_DISPLAY8) {
            err_print("worker diff: warning: %s is an 8-bit PNG/PPM: %s is converted to 8-bit display values "
                      "as the PNG writer does, and the error is measured on those, not on linear radiance\n",
                      files[1 - i], files[i]);
            if (to_display(&img[i], e) < 0)
                goto done;
        }
    if (mask_arg && load_mask(mask_arg, img[0].w, img[0].h, &mask, e) < 0)
        goto done;
    const struct img_mask *mp = mask_arg ? &mask : NULL;
    f->mask_pixels = mp ? mask.count : 0;
    if (metrics_compare_masked(&img[0], &img[1], block, mp, &f->m, e) < 0 ||
        (*domain == IMG_LINEAR ? flip_hdr : flip_ldr)(&img[0], &img[1], mp, NULL, &f->flip, e) < 0) {
        snprintf(e->file, sizeof e->file, "%s", files[1]);
        goto done;
    }
    if (map_path && write_map(map_path, &img[0], &img[1], e) < 0)
        goto done;
    rc = 0;
done:
    mask_free(&mask);
    image_f_free(&img[0]);
    image_f_free(&img[1]);
    return rc;
}

int diff_main(int argc, char **argv)
{
    const char *files[2] = {0}, *map_path = NULL, *mask_arg = NULL;
    int nfiles = 0, json = 0;
    double max_rmse = -1, block = 1;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--block")) {
            if (i + 1 >= argc || parse_number(argv[++i], &block) < 0 || block != floor(block) || block < 1 ||
                block > 65536) {
                err_print("worker diff: --block needs a whole number of pixels in [1, 65536]\n");
                return 2;
            }
        } else if (!strcmp(argv[i], "--max-rmse")) {
            if (i + 1 >= argc || parse_number(argv[++i], &max_rmse) < 0 || max_rmse < 0) {
                err_print("worker diff: --max-rmse needs a number >= 0\n");
                return 2;
            }
        } else if (!strcmp(argv[i], "--map")) {
            if (i + 1 >= argc || !argv[i + 1][0]) {
                err_print("worker diff: --map needs a file name (a PNG is written there)\n");
                return 2;
            }
            map_path = argv[++i];
        } else if (!strcmp(argv[i], "--mask")) {
            if (i + 1 >= argc || !argv[i + 1][0]) {
                err_print("worker diff: --mask needs x0,y0,x1,y1 (pixels, x1 and y1 exclusive) or an image "
                          "file (white = counted)\n");
                return 2;
            }
            mask_arg = argv[++i];
        } else if (!strcmp(argv[i], "--json")) {
            json = 1;
        } else if (!strcmp(argv[i], "--quiet") || !strcmp(argv[i], "-q")) {
            continue; /* a common option; diff draws no progress anyway */
        } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: worker diff A B [--json] [--map F.png] [--mask x0,y0,x1,y1|M.png] [--max-rmse X]\n"
                   "                      [--block N] [--quiet]\n"
                   "error metrics of B against reference A (EXR, PFM, PNG or PPM): in linear radiance when\n"
                   "both are float images (EXR, PFM), else on 8-bit display values; flip is HDR-FLIP on\n"
                   "linear images, LDR-FLIP on 8-bit ones. exit 1 when rmse is over X. --map writes a\n"
                   "false-colour PNG of the per-pixel relative error. --mask counts only a rectangle's\n"
                   "pixels (y down from the top row; x1, y1 exclusive) or an image's white ones.\n");
            return 0;
        } else if (argv[i][0] == '-' && argv[i][1]) {
            err_print("worker diff: unknown option %s; see worker --help\n", argv[i]);
            return 2;
        } else if (nfiles < 2) {
            files[nfiles++] = argv[i];
        } else {
            err_print("worker diff: expected two images, got a third: %s\n", argv[i]);
            return 2;
        }
    }
    if (nfiles != 2) {
        err_print("worker diff: expected two images (reference, then image); see worker --help\n");
        return 2;
    }
    struct diff_figures f = {0};
    const struct metrics *mp = &f.m;
    struct err e = {0};
    if (map_path && fileio_output_ok(map_path, files, 2, &e) < 0) {
        err_print("worker diff: --map %s\n", e.msg);
        return 2;
    }
    if (measure(files, (int)block, map_path, mask_arg, &f, &e) < 0) {
        cli_print_err(&e);
        return 2;
    }
    const char *flip_name = f.flip.hdr ? "HDR-FLIP" : "LDR-FLIP";
    if (json) {
        printf("{");
        print_number("mse", mp->mse, ", ");
        print_number("rmse", mp->rmse, ", ");
        print_number("relmse", mp->relmse, ", ");
        print_number("relmse_robust", mp->relmse_robust, ", ");
        print_number("psnr", mp->psnr, ", ");
        print_number("flip", f.flip.mean, ", ");
        printf("\"flip_metric\": \"%s\", ", flip_name);
        if (f.flip.hdr)
            printf("\"flip_exposures\": {\"start\": %.6g, \"stop\": %.6g, \"count\": %d}, ",
                   f.flip.start_exposure, f.flip.stop_exposure, f.flip.n_exposures);
        if (f.mask_pixels)
            printf("\"mask_pixels\": %zu, ", f.mask_pixels);
        printf("\"domain\": \"%s\"}\n", image_domain_name(f.domain));
    } else {
        printf("mse %.9g\nrmse %.9g\nrelmse %.9g\nrelmse_robust %.9g\npsnr %.4f\n", mp->mse, mp->rmse,
               mp->relmse, mp->relmse_robust, mp->psnr);
        printf("flip %.6f %s", f.flip.mean, flip_name);
        if (f.flip.hdr)
            printf(" (%d exposures, %.4f to %.4f stops)", f.flip.n_exposures, f.flip.start_exposure,
                   f.flip.stop_exposure);
        printf("\ndomain %s\n", image_domain_name(f.domain));
        if (f.mask_pixels)
            printf("mask %zu pixels\n", f.mask_pixels);
    }
    if (max_rmse >= 0 && mp->rmse > max_rmse) {
        err_print("worker diff: rmse %.6g is over --max-rmse %g\n", mp->rmse, max_rmse);
        return 1;
    }
    return 0;
}
