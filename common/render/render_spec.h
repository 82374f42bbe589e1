/* render_spec: everything that changes a render's pixels, described once in one table of rows (key,
   type, default, range, label). The job file's keys, the cache key's text, the sidecar's settings,
   summary.csv's settings columns and the render settings all come from it: a setting added later is
   one row (render_spec.c) and one field here. */
#ifndef RENDER_SPEC_H
#define RENDER_SPEC_H

#include <stddef.h>
#include <stdint.h>

#include "base/err.h"
#include "base/json.h"
#include "base/sbuf.h"
#include "render_types.h"
#include "sample/sampler.h"

/* One sampler of a render: its kind and its threshold (the minimum spacing in a 100 x 100 domain). */
struct sampler_spec {
    enum sampler_kind kind;
    double threshold;
};

struct render_spec {
    int width, height;         /* height 0: width / the camera's aspect */
    struct sampler_spec pixel; /* sampler:, threshold: */
    struct sampler_spec light; /* light_sampler:, light_threshold: (the pixel sampler's when not given) */
    int light_sampling;        /* 0: no importance sampling of lights */
    enum integrator integrator;
    int dims_all;     /* sampler_dims: 1 all (every 2D decision from the pixel sampler), 0 pixel_light */
    int roulette;     /* russian_roulette: 1 on, 0 off, -1 the integrator's default (render_spec_roulette) */
    int poisson_pool; /* pooled Poisson sets: how many (0: fresh sets) */
    enum poisson_domain poisson_domain; /* fresh Poisson sets: torus (default, unbiased) or square */
    int max_depth;
    uint64_t seed;
};

/* A row's value: a whole number in [lo, hi] (an int; the seed a uint64_t), a threshold in (0, 100],
   or one of the row's names (its index): a sampler kind, a choice, or a yes/no (false, true). */
enum render_spec_type { RS_INT, RS_U64, RS_THRESHOLD, RS_SAMPLER, RS_CHOICE, RS_BOOL };

struct render_spec_row {
    const char *key; /* the job file's key, the sidecar's and summary.csv's name */
    enum render_spec_type type;
    size_t offset;                     /* of the field in struct render_spec */
    long lo, hi;                       /* RS_INT, RS_U64: the job file's range */
    const char *const *(*names)(void); /* a named type's values by index, NULL-ended; else NULL */
    double default_value;
    int pixels;        /* 1: changes pixels (every row today) */
    const char *label; /* for people: a report's column head */
    int csv_front;     /* summary.csv: 1 among its first columns (where threshold, light_threshold and
                          seed were before this table), 0 just before image */
};

/* The rows, in the order the sidecar and summary.csv write them (*n of them); the row of key or NULL. */
const struct render_spec_row *render_spec_rows(int *n);
const struct render_spec_row *render_spec_find(const char *key);

/* Every row's default (width 300, height 0, random samplers at 5, ...). */
void render_spec_defaults(struct render_spec *s);

/* A field through its row: a threshold's address; any other's value put (an enum's as its int). */
double *render_spec_threshold(struct render_spec *s, const struct render_spec_row *r);
void render_spec_put(struct render_spec *s, const struct render_spec_row *r, uint64_t v);

/* Whether v is in row r's range: the one place a setting's range is checked. */
int render_spec_in_range(const struct render_spec_row *r, double v);
/* What row r's text must be, for a message ("a whole number in [1, 32768]", "torus or square"). */
const char *render_spec_expected(const struct render_spec_row *r, char *buf, size_t n);

/* Whether paths end by Russian roulette: russian_roulette when given, else the integrator's default. */
int render_spec_roulette(const struct render_spec *s);

/* Row r's value as the sidecar and summary.csv write it (a threshold read back exactly, roulette
   resolved to on / off), into buf (n bytes); returns buf. set_text reads it back: 0, or -1 (not
   such a value, out of range; a seed may be any 64-bit one a render had). */
const char *render_spec_text(const struct render_spec *s, const struct render_spec_row *r, char *buf,
                             size_t n);
int render_spec_set_text(struct render_spec *s, const struct render_spec_row *r, const char *text);

/* Every row as a member of the JSON object being written (numbers, names as strings, yes/no as bools). */
void render_spec_json(const struct render_spec *s, struct json *js);
/* summary.csv: the values (s NULL: the keys) of the rows whose csv_front is front, each then a comma. */
void render_spec_csv(const struct render_spec *s, int front, struct sbuf *b);

/* The canonical text every cache key (images and references) is hashed from: size, samplers and
   thresholds, depth, seed, pool, light sampling, then `middle` (the caller's), the worker's version,
   the integrator's tag, sampler_dims, the sets' rules and roulette, in the order and spelling earlier
   keys used; a row added later adds " key value" when not at its default. Into buf (n bytes);
   returns the text's length (cut to n - 1 when longer). */
int render_spec_key_text(const struct render_spec *s, const char *middle, char *buf, size_t n);

/* The render settings of s at w x h pixels with the given seed. */
struct render_settings render_spec_settings(const struct render_spec *s, int w, int h, uint64_t seed);

/* s's pixel and light samplers for an image of the given seed (their Poisson pools seeded from it),
   domains set. 0, or -1 with e filled and both NULL (nothing to free). */
int render_spec_samplers_new(const struct render_spec *s, uint64_t seed, struct sampler **pix,
                             struct sampler **light, struct err *e);

#endif
