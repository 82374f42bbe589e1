/* render_spec: everything that changes a render's pixels, described once in one table of rows
   (key, type, default, range, label). The job file's keys, the cache key's text, the sidecar's
   settings, summary.csv's settings columns and the render settings all come from that table: a
   setting added later is one row (render_spec.c) and one field here. */
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
    int dims_all; /* sampler_dims: 1 all (every 2D decision from the pixel sampler), 0 pixel_light */
    int roulette; /* russian_roulette: 1 on, 0 off, -1 the integrator's default (render_spec_roulette) */
    int poisson_pool;                   /* pooled Poisson sets: how many (0: fresh sets) */
    enum poisson_domain poisson_domain; /* fresh Poisson sets: torus (default, unbiased) or square */
    int max_depth;
    uint64_t seed;
};

/* How a row's value is held and read: a whole number in [lo, hi] (an int, or the uint64_t seed), a
   threshold in (0, 100], a sampler kind, one of a list of names (its index), or a yes/no. */
enum render_spec_type { RS_INT, RS_U64, RS_THRESHOLD, RS_SAMPLER, RS_CHOICE, RS_BOOL };

struct render_spec_row {
    const char *key; /* the job file's key, the sidecar's and summary.csv's column name */
    enum render_spec_type type;
    size_t offset;            /* of the field in struct render_spec */
    long lo, hi;              /* RS_INT, RS_U64: the range */
    const char *const *(*names)(void); /* RS_CHOICE: the value names, by index, NULL-ended */
    double default_value;     /* a threshold; any other type's value as a number */
    int pixels;               /* 1: changes pixels (every row today; a row that does not is named) */
    const char *label;        /* for people: a report's column head */
    int csv_front;            /* summary.csv: 1 among its first columns (where readers found threshold,
                                 light_threshold and seed before this table), 0 just before image */
};

/* The rows, in the order the sidecar and summary.csv write them; *n their count. */
const struct render_spec_row *render_spec_rows(int *n);
/* The row of key, or NULL. */
const struct render_spec_row *render_spec_find(const char *key);

/* Every row's default (width 300, height 0, random samplers at 5, ...). */
void render_spec_defaults(struct render_spec *s);

/* Field access through a row: RS_U64 reads the seed, every other type an int (an enum's value). */
uint64_t render_spec_get(const struct render_spec *s, const struct render_spec_row *r);
double render_spec_get_threshold(const struct render_spec *s, const struct render_spec_row *r);
void render_spec_put(struct render_spec *s, const struct render_spec_row *r, uint64_t v);
void render_spec_put_threshold(struct render_spec *s, const struct render_spec_row *r, double t);

/* Whether a value is in row r's range: the one place a setting's range is checked. */
int render_spec_in_range(const struct render_spec_row *r, double v);

/* Whether paths end by Russian roulette: russian_roulette when given, else the integrator's default. */
int render_spec_roulette(const struct render_spec *s);

/* Row r's value as text, as the sidecar and summary.csv write it (a threshold read back exactly,
   roulette resolved to on / off, a yes/no as true / false). Into buf (n bytes); returns buf. */
const char *render_spec_text(const struct render_spec *s, const struct render_spec_row *r, char *buf,
                             size_t n);
/* Row r's value from text as render_spec_text writes it: 0, or -1 (not such a value, out of range;
   a seed may be any 64-bit one a render had, the job file's range being for the key). */
int render_spec_set_text(struct render_spec *s, const struct render_spec_row *r, const char *text);

/* What row r's text must be, for a message: "a whole number in [1, 32768]", "a number in (0, 100]",
   "one of torus, square", "true or false". Into buf (n bytes); returns buf. */
const char *render_spec_expected(const struct render_spec_row *r, char *buf, size_t n);

/* Every row as a member of the JSON object being written (numbers as numbers, names as strings). */
void render_spec_json(const struct render_spec *s, struct json *js);
/* summary.csv: the keys, then the values, of the rows whose csv_front is front, each followed by a
   comma (both parts together: every row). */
void render_spec_csv_header(struct sbuf *b, int front);
void render_spec_csv_row(const struct render_spec *s, int front, struct sbuf *b);
/* A spec from a row of named fields (names[i] holds values[i], n of each): every row's column must
   be there. 0, or -1 with e naming the column (at file, line). */
int render_spec_from_fields(struct render_spec *s, const char *const *names, const char *const *values,
                            int n, const char *file, int line, struct err *e);

/* The canonical text of s, the one text every cache key (images and references) is hashed from:
   size, samplers and thresholds, depth, seed, pool, light sampling, then `middle` (the caller's
   addition), the worker's version, the integrator's tag, sampler_dims, the sets' rules and roulette,
   in the order and spelling earlier keys used; a row added later adds " key value" when not at its
   default. Into buf (n bytes); returns the text's length (cut to n - 1 when longer). */
int render_spec_key_text(const struct render_spec *s, const char *middle, char *buf, size_t n);

/* The render settings of s at w x h pixels with the given seed. */
struct render_settings render_spec_settings(const struct render_spec *s, int w, int h, uint64_t seed);

/* s's pixel and light samplers for an image of the given seed (their Poisson pools seeded from it),
   domains set. 0, or -1 with e filled and both NULL (nothing to free). */
int render_spec_samplers_new(const struct render_spec *s, uint64_t seed, struct sampler **pix,
                             struct sampler **light, struct err *e);

#endif
