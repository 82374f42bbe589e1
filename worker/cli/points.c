/* points: `worker points SAMPLER THRESHOLD [options]`: one sample set as CSV / SVG, its spectrum and
   statistics, or a pixel's padded dimensions. */
#include "points.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/err.h"
#include "base/fileio.h"
#include "base/rng.h"
#include "base/sbuf.h"
#include "points_analysis.h"
#include "sample/padding.h"
#include "sample/sampler.h"
#include "job/job.h"
#include "job/job_path.h"

static const char points_usage[] = "usage: worker points SAMPLER THRESHOLD [--seed S] [--sets M] [--svg F] "
                                   "[--spectrum F.png] [--radial F.svg] "
                                   "[--stats] [--padded K]\n";

/* Most sets --sets may average (the work limits bound them further). */
#define POINTS_MAX_SETS 100000
/* Most dimensions --padded prints: the pixel's own and 63 padded (lens, shutter and 20 bounces'
   three decisions under sampler_dims: all; the render pads 16 bounces). */
#define POINTS_MAX_PADDED 64

struct points_args {
    enum sampler_kind kind;
    double threshold;
    uint64_t seed;
    const char *svg_path; /* NULL: no picture */
    int padded;           /* --padded K: K dimensions per sample (0: none) */
    struct points_analysis an;
};

/* A whole decimal number in [0, 2^64 - 1]: no sign, no trailing garbage. */
static int parse_seed(const char *s, uint64_t *out)
{
    if (s[0] < '0' || s[0] > '9')
        return -1;
    char *end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (*end || errno == ERANGE)
        return -1;
    *out = (uint64_t)v;
    return 0;
}

/* Whether the file of option opt can go where it is named (a writable folder, not a folder itself):
   0, or 2 (bad usage, before anything is drawn) after one line on stderr. */
static int place_ok(const char *opt, const char *path)
{
    if (!path)
        return 0;
    char dir[4096];
    job_path_dir(path, dir, sizeof dir);
    struct stat st;
    struct err e = {0};
    if (fileio_output_ok(path, NULL, 0, &e) < 0) {
        err_print("worker points: %s %s\n", opt, e.msg);
        return 2;
    }
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        err_print("worker points: %s %s: no folder %s\n", opt, path, dir);
        return 2;
    }
    if (access(dir, W_OK | X_OK) != 0) {
        err_print("worker points: %s %s: cannot write in %s: %s\n", opt, path, dir, strerror(errno));
        return 2;
    }
    return 0;
}

/* Whether arg is option name, alone or as name=value. */
static int file_option(const char *arg, const char *name)
{
    const size_t len = strlen(name);
    return !strncmp(arg, name, len) && (arg[len] == '\0' || arg[len] == '=');
}

/* The value of option argv[*i] (`--name V` or `--name=V`, advancing *i past V), a whole number
   in [1, limit], or any (parse_seed's) when limit is 0: 0, or 2 after one line on stderr. */
static int whole_option(int argc, char **argv, int *i, int limit, uint64_t *out)
{
    const char *arg = argv[*i];
    const int len = (int)strcspn(arg, "=");
    const char *v = arg[len] == '=' ? arg + len + 1 : (*i + 1 < argc ? argv[++*i] : NULL);
    if (!v) {
        err_print("worker points: %.*s needs a value; %s", len, arg, points_usage);
        return 2;
    }
    if (parse_seed(v, out) == 0 && (limit == 0 || (*out >= 1 && *out <= (uint64_t)limit)))
        return 0;
    if (limit == 0)
        err_print("worker points: %.*s: must be a whole number >= 0, got \"%.40s\"\n", len, arg, v);
    else
        err_print("worker points: %.*s: must be a whole number in [1, %d], got \"%.40s\"\n", len, arg, limit,
                  v);
    return 2;
}

/* Fill a from argv. Returns 0, or the exit status after one line on stderr; --help prints the
   usage, sets done and returns 0. */
static int points_parse(int argc, char **argv, struct points_args *a, int *done)
{
    const char *positional[2] = {NULL, NULL};
    int npositional = 0;
    *done = 0;
    *a = (struct points_args){.seed = 1, .an = {.sets = 1, .seed = 1}};
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) {
            fputs(points_usage, stdout);
            *done = 1;
            return 0;
        } else if (file_option(arg, "--seed")) {
            if (whole_option(argc, argv, &i, 0, &a->seed) != 0)
                return 2;
        } else if (file_option(arg, "--sets") || file_option(arg, "--padded")) {
            const int sets = arg[2] == 's', limit = sets ? POINTS_MAX_SETS : POINTS_MAX_PADDED;
            uint64_t v;
            if (whole_option(argc, argv, &i, limit, &v) != 0)
                return 2;
            *(sets ? &a->an.sets : &a->padded) = (int)v;
        } else if (file_option(arg, "--svg") || file_option(arg, "--spectrum") ||
                   file_option(arg, "--radial")) {
            const size_t len = strcspn(arg, "=");
            const char *v = arg[len] == '=' ? arg + len + 1 : (i + 1 < argc ? argv[++i] : NULL);
            if (!v || !*v) {
                err_print("worker points: %.*s needs a file name; %s", (int)len, arg, points_usage);
                return 2;
            }
            const char **slot = !strncmp(arg, "--svg", len)        ? &a->svg_path
                                : !strncmp(arg, "--spectrum", len) ? &a->an.spectrum_path
                                                                   : &a->an.radial_path;
            *slot = v;
        } else if (!strcmp(arg, "--stats")) {
            a->an.stats = 1;
        } else if (!strcmp(arg, "--quiet") || !strcmp(arg, "-q")) {
            continue; /* a common option; points draws no progress anyway */
        } else if (arg[0] == '-' && arg[1] == '-') {
            err_print("worker points: unknown option %.40s; %s", arg, points_usage);
            return 2;
        } else if (npositional < 2) {
            positional[npositional++] = arg; /* "-1" too: a threshold, refused below */
        } else {
            err_print("worker points: unexpected argument \"%.40s\"; %s", arg, points_usage);
            return 2;
        }
    }
    if (npositional < 2) {
        err_print("worker points: expected a sampler and a threshold; %s", points_usage);
        return 2;
    }
    char why[400];
    struct render_spec spec; /* the threshold read as a job file's (render_spec's row) */
    if (sampler_kind_parse(positional[0], &a->kind) < 0) {
        err_print("worker points: %s\n", job_unknown_sampler(positional[0], why, sizeof why));
        return 2;
    }
    if (render_spec_set_text(&spec, render_spec_find("threshold"), positional[1]) < 0) {
        err_print("worker points: threshold: must be a number in (0, 100], got \"%.40s\"\n", positional[1]);
        return 2;
    }
    a->threshold = spec.pixel.threshold;
    if (a->seed > UINT64_MAX - (uint64_t)(a->an.sets - 1)) {
        err_print("worker points: --seed %llu with --sets %d runs past the largest seed\n",
                  (unsigned long long)a->seed, a->an.sets);
        return 2;
    }
    if (a->padded && (a->svg_path || points_analysis_wanted(&a->an) || a->an.sets != 1)) {
        err_print("worker points: --padded prints dimensions as CSV; it takes no --svg, --sets, --spectrum, "
                  "--radial or --stats\n");
        return 2;
    }
    a->an.seed = a->seed;
    a->an.threshold = a->threshold;
    const char *const files[3][2] = {
        {"--svg", a->svg_path}, {"--spectrum", a->an.spectrum_path}, {"--radial", a->an.radial_path}};
    int rc = 0;
    for (int k = 0; k < 3 && !rc; k++)
        rc = place_ok(files[k][0], files[k][1]);
    return rc;
}

/* The set as an SVG picture: the unit square (y up) and a dot per point, written atomically. */
static int write_svg(const char *path, const struct points_args *a, const struct pt2 *p, size_t n,
                     struct err *e)
{
    const double side = 500.0, margin = 10.0;
    double dot = 0.35 * side / sqrt((double)n);
    dot = dot < 0.4 ? 0.4 : dot > 4.0 ? 4.0 : dot;
    struct sbuf b = {0};
    sbuf_printf(&b, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    sbuf_printf(
        &b, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" viewBox=\"0 0 %g %g\">\n",
        side + 2 * margin, side + 2 * margin, side + 2 * margin, side + 2 * margin);
    sbuf_printf(&b, "<title>%s, threshold %g, seed %llu: %zu points</title>\n", sampler_kind_name(a->kind),
                a->threshold, (unsigned long long)a->seed, n);
    sbuf_printf(&b, "<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" fill=\"white\" stroke=\"black\"/>\n",
                margin, margin, side, side);
    sbuf_printf(&b, "<g fill=\"black\">\n");
    for (size_t k = 0; k < n; k++)
        sbuf_printf(&b, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\"/>\n", margin + p[k].x * side,
                    margin + (1.0 - p[k].y) * side, dot);
    sbuf_printf(&b, "</g>\n</svg>\n");
    int rc = b.oom ? err_set(e, path, 0, 0, "out of memory while drawing %zu points", n)
                   : fileio_write_atomic(path, b.buf, b.len, e);
    sbuf_free(&b);
    return rc;
}

/* --padded K: the pixel (0, 0) of a job with seed a->seed under sampler_dims: all, one row per
   camera sample s: dimension 0 its point of the pixel's set, dimensions 1 .. K-1 its points of
   padded slots 0 .. K-2 (lens, shutter, then per bounce direction, light point, choice). */
static int print_padded(const struct points_args *a, struct sampler *s, struct pt2 *p)
{
    struct rng rng;
    struct err e;
    struct padding pad;
    rng_pixel(&rng, a->seed, 0, 0, 0); /* the render's pixel stream */
    size_t n = sampler_draw(s, &rng, p);
    if (padding_init(&pad, s, a->padded, &e) < 0) {
        err_print("worker points: %s\n", e.msg);
        return 1;
    }
    padding_pixel(&pad, a->seed, 0, 0, n);
    for (size_t k = 0; k < n; k++) {
        printf("%.17g,%.17g", p[k].x, p[k].y);
        for (int d = 1; d < a->padded; d++) {
            struct pt2 q = padding_point(&pad, d - 1, (uint32_t)k);
            printf(",%.17g,%.17g", q.x, q.y);
        }
        putchar('\n');
    }
    padding_release(&pad);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        err_print("worker points: writing the points: %s\n", strerror(errno));
        return 1;
    }
    return 0;
}

int points_main(int argc, char **argv)
{
    struct points_args a;
    int done;
    int rc = points_parse(argc, argv, &a, &done);
    if (rc != 0 || done)
        return rc;

    struct err e;
    struct sampler *s = sampler_new(a.kind, a.threshold, 0, 0, &e);
    if (!s) {
        err_print("worker points: %s\n", e.msg);
        return 2;
    }
    struct pt2 *p = malloc(sampler_set_capacity(s) * sizeof *p);
    if (!p) {
        err_print("worker points: out of memory for %zu points\n", sampler_set_capacity(s));
        sampler_free(s);
        return 1;
    }
    if (a.padded) {
        rc = print_padded(&a, s, p);
        sampler_free(s);
        free(p);
        return rc;
    }
    struct rng rng;
    rng_seed(&rng, a.seed, 0);
    size_t n = sampler_draw(s, &rng, p);

    rc = points_analysis_check(&a.an, n);
    if (rc == 0 && a.svg_path && write_svg(a.svg_path, &a, p, n, &e) != 0) {
        char line[2048];
        err_format(&e, line, sizeof line);
        err_print("worker points: %s\n", line);
        rc = 1;
    }
    if (rc == 0 && !a.an.stats) { /* one "x,y" line per point, nothing else: a line count is the set's size */
        /* %.17g: each double read back exactly, so every point lands in its cell (6 decimals put
           points within 1e-6 of a boundary into the next cell) */
        for (size_t k = 0; k < n; k++)
            printf("%.17g,%.17g\n", p[k].x, p[k].y);
        if (fflush(stdout) != 0 || ferror(stdout)) {
            err_print("worker points: writing the points: %s\n", strerror(errno));
            rc = 1;
        }
    }
    if (rc == 0 && points_analysis_wanted(&a.an))
        rc = points_analysis_run(&a.an, s, p);
    sampler_free(s);
    free(p);
    return rc;
}
