/* render_spec: the table of everything that changes pixels, and what is made from it. */
#include "render_spec.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/rng.h"
#include "image/image.h"

_Static_assert(sizeof(enum sampler_kind) == sizeof(int) && sizeof(enum integrator) == sizeof(int) &&
                   sizeof(enum poisson_domain) == sizeof(int),
               "an enum field is read and written as an int");

/* The names of the named rows' values, by index (integrator.c's, sampler_kind.c's, sampler.c's). */
#define NAMES(fn, ...)                                                                                       \
    static const char *const *fn(void)                                                                       \
    {                                                                                                        \
        static const char *const names[] = {__VA_ARGS__, NULL};                                              \
        return names;                                                                                        \
    }
NAMES(dims_names, "pixel_light", "all")
NAMES(roulette_names, "off", "on")
NAMES(bool_names, "false", "true")

#define AT(field) offsetof(struct render_spec, field)
/* key, type, field, lo, hi, names, default, changes pixels, label, summary.csv's place. In the order
   the sidecar and summary.csv write them; a new setting is a row at the end (and a field in struct
   render_spec). */
static const struct render_spec_row rows[] = {
    {"width", RS_INT, AT(width), 1, IMAGE_MAX_SIDE, NULL, 300, 1, "width", 0},
    {"height", RS_INT, AT(height), 1, IMAGE_MAX_SIDE, NULL, 0, 1, "height", 0},
    {"sampler", RS_SAMPLER, AT(pixel.kind), 0, 0, sampler_kind_names, SAMPLER_RANDOM, 1, "sampler", 0},
    {"threshold", RS_THRESHOLD, AT(pixel.threshold), 0, 100, NULL, 5, 1, "threshold", 1},
    {"light_sampler", RS_SAMPLER, AT(light.kind), 0, 0, sampler_kind_names, SAMPLER_RANDOM, 1,
     "light sampler", 0},
    {"light_threshold", RS_THRESHOLD, AT(light.threshold), 0, 100, NULL, 5, 1, "light threshold", 1},
    {"light_sampling", RS_BOOL, AT(light_sampling), 0, 1, bool_names, 1, 1, "light sampling", 0},
    {"integrator", RS_CHOICE, AT(integrator), 0, 0, integrator_names, INTEGRATOR_MIXTURE, 1, "integrator", 0},
    {"sampler_dims", RS_CHOICE, AT(dims_all), 0, 0, dims_names, 0, 1, "sampler dims", 0},
    {"russian_roulette", RS_CHOICE, AT(roulette), 0, 0, roulette_names, -1, 1, "russian roulette", 0},
    {"poisson_pool", RS_INT, AT(poisson_pool), 0, 65536, NULL, 0, 1, "poisson pool", 0},
    {"poisson_domain", RS_CHOICE, AT(poisson_domain), 0, 0, poisson_domain_names, POISSON_TORUS, 1,
     "poisson domain", 0},
    {"max_depth", RS_INT, AT(max_depth), 1, 10000, NULL, 50, 1, "max depth", 0},
    {"seed", RS_U64, AT(seed), 0, 2147483647L, NULL, 1, 1, "seed", 1},
};
#define N_ROWS ((int)(sizeof rows / sizeof rows[0]))
/* The rows render_spec_key_text spells as earlier cache keys did; later rows add " key value". */
#define KEY_TEXT_ROWS 14

const struct render_spec_row *render_spec_rows(int *n)
{
    *n = N_ROWS;
    return rows;
}

const struct render_spec_row *render_spec_find(const char *key)
{
    for (int i = 0; i < N_ROWS; i++)
        if (!strcmp(rows[i].key, key))
            return &rows[i];
    return NULL;
}

static void *field(const struct render_spec *s, const struct render_spec_row *r)
{
    return (char *)(uintptr_t)s + r->offset; /* const taken off here only: the writers take a mutable s */
}

/* A field's value through its row (an enum's as its int; the seed a uint64_t). */
static uint64_t render_spec_get(const struct render_spec *s, const struct render_spec_row *r)
{
    const int *i = field(s, r);
    return r->type == RS_U64 ? *(uint64_t *)field(s, r) : (uint64_t)(int64_t)*i;
}

double *render_spec_threshold(struct render_spec *s, const struct render_spec_row *r)
{
    return (double *)field(s, r);
}

void render_spec_put(struct render_spec *s, const struct render_spec_row *r, uint64_t v)
{
    if (r->type == RS_U64)
        *(uint64_t *)field(s, r) = v;
    else
        *(int *)field(s, r) = (int)(int64_t)v;
}

void render_spec_defaults(struct render_spec *s)
{
    memset(s, 0, sizeof *s);
    for (int i = 0; i < N_ROWS; i++)
        if (rows[i].type == RS_THRESHOLD)
            *render_spec_threshold(s, &rows[i]) = rows[i].default_value;
        else
            render_spec_put(s, &rows[i], (uint64_t)(int64_t)rows[i].default_value);
}

int render_spec_in_range(const struct render_spec_row *r, double v)
{
    return r->type == RS_THRESHOLD ? sampler_threshold_valid(v) : v >= (double)r->lo && v <= (double)r->hi;
}

int render_spec_roulette(const struct render_spec *s)
{
    return s->roulette < 0 ? integrator_traits(s->integrator)->roulette : s->roulette;
}

const char *render_spec_text(const struct render_spec *s, const struct render_spec_row *r, char *buf,
                             size_t n)
{
    const uint64_t v = render_spec_get(s, r);
    const double t = r->type == RS_THRESHOLD ? *(double *)field(s, r) : 0;
    if (r->type == RS_THRESHOLD) /* %g when that reads back, else all the digits it takes */
        for (int digits = 6; digits <= 17 && (snprintf(buf, n, "%.*g", digits, t), strtod(buf, NULL) != t);)
            digits += digits == 6 ? 9 : 1;
    else if (r->names) /* roulette's -1 resolved: the text says what the render does */
        snprintf(buf, n, "%s", r->names()[r->offset == AT(roulette) ? render_spec_roulette(s) : (int)v]);
    else if (r->type == RS_U64)
        snprintf(buf, n, "%llu", (unsigned long long)v);
    else
        snprintf(buf, n, "%d", (int)v);
    return buf;
}

int render_spec_set_text(struct render_spec *s, const struct render_spec_row *r, const char *text)
{
    char *end;
    errno = 0;
    for (int i = 0; r->names && r->names()[i]; i++)
        if (!strcmp(text, r->names()[i])) {
            render_spec_put(s, r, (uint64_t)i);
            return 0;
        }
    if (r->names || !*text ||
        strspn(text, r->type == RS_THRESHOLD ? "0123456789+-.eE" : "0123456789") != strlen(text))
        return -1; /* decimal only: strtod alone takes hex (0x10) and leading blanks */
    if (r->type == RS_THRESHOLD) {
        double t = strtod(text, &end);
        return *end || !render_spec_in_range(r, t) ? -1 : (*render_spec_threshold(s, r) = t, 0);
    }
    /* any seed a render had (a reference half's own is mixed to 64 bits): the row's range is the key's */
    unsigned long long v = strtoull(text, &end, 10);
    if (errno || (r->type != RS_U64 && !render_spec_in_range(r, (double)v)))
        return -1;
    render_spec_put(s, r, (uint64_t)v);
    return 0;
}

const char *render_spec_expected(const struct render_spec_row *r, char *buf, size_t n)
{
    const char *const *names = r->names ? r->names() : NULL;
    if (r->type == RS_THRESHOLD)
        snprintf(buf, n, "a number in (0, 100]");
    else if (!names)
        snprintf(buf, n, "a whole number in [%ld, %ld]", r->lo, r->hi);
    for (size_t i = 0, used = 0; names && names[i] && used < n; i++) /* "a, b or c" */
        used += (size_t)snprintf(buf + used, n - used, "%s%s",
                                 !i             ? ""
                                 : names[i + 1] ? ", "
                                                : " or ",
                                 names[i]);
    return buf;
}

void render_spec_json(const struct render_spec *s, struct json *js)
{
    char text[64];
    for (const struct render_spec_row *r = rows; r < rows + N_ROWS; r++) {
        render_spec_text(s, r, text, sizeof text);
        if (r->type == RS_BOOL)
            json_bool(js, r->key, (int)render_spec_get(s, r));
        else if (r->names)
            json_string(js, r->key, text);
        else
            json_number_text(js, r->key, text);
    }
}

void render_spec_csv(const struct render_spec *s, int front, struct sbuf *b)
{
    char text[64];
    for (const struct render_spec_row *r = rows; r < rows + N_ROWS; r++)
        if (r->csv_front == front)
            sbuf_printf(b, "%s,", s ? render_spec_text(s, r, text, sizeof text) : r->key);
}

/* What a key adds for the sets s's samplers make beyond the rows it prints: the Poisson domain when
   a sampler pools (poisson), the padding's version under sampler_dims: all ("" else), so that an
   image rendered by an earlier rule is never found current. */
static const char *sets_tag(const struct render_spec *s, char *buf, size_t n)
{
    const int pooled =
        sampler_kind_has(s->pixel.kind, SAMPLER_POOLED) || sampler_kind_has(s->light.kind, SAMPLER_POOLED);
    const char *pad = s->dims_all ? " padded uniformly" : "";
    if (!pooled)
        snprintf(buf, n, "%s", pad);
    else /* the kind that pools has a domain: its name and the domain's (the hashes of old) */
        snprintf(buf, n, " %s %s%s", sampler_kind_name(SAMPLER_POISSON),
                 poisson_domain_name(s->poisson_domain), pad);
    return buf;
}

int render_spec_key_text(const struct render_spec *s, const char *middle, char *buf, size_t n)
{
    char tag[64], text[64];
    int len = snprintf(
        buf, n, "%dx%d %s %.17g %s %.17g depth %d seed %llu pool %d lights %d%s worker %s%s%s%s%s", s->width,
        s->height, sampler_kind_name(s->pixel.kind), s->pixel.threshold, sampler_kind_name(s->light.kind),
        s->light.threshold, s->max_depth, (unsigned long long)s->seed, s->poisson_pool, s->light_sampling,
        middle, WORKER_VERSION, integrator_traits(s->integrator)->hash_tag, s->dims_all ? " dims all" : "",
        sets_tag(s, tag, sizeof tag), render_spec_roulette(s) ? " roulette" : "");
    struct render_spec dflt;
    render_spec_defaults(&dflt);
    for (int i = KEY_TEXT_ROWS; i < N_ROWS && len >= 0 && (size_t)len < n; i++)
        if (strcmp(render_spec_text(s, &rows[i], text, sizeof text),
                   render_spec_text(&dflt, &rows[i], tag, sizeof tag)))
            len += snprintf(buf + len, n - (size_t)len, " %s %s", rows[i].key, text);
    return len < 0 ? 0 : (size_t)len >= n ? (int)n - 1 : len;
}

struct render_settings render_spec_settings(const struct render_spec *s, int w, int h, uint64_t seed)
{
    return (struct render_settings){
        w, h, s->max_depth, seed, !s->light_sampling, s->integrator, s->dims_all, render_spec_roulette(s)};
}

int render_spec_samplers_new(const struct render_spec *s, uint64_t seed, struct sampler **pix,
                             struct sampler **light, struct err *e)
{
    uint64_t pool_seed = rng_mix64(seed ^ 0x706f6f6cULL); /* "pool": the pools' own stream */
    *light = NULL;
    if (!(*pix = sampler_new(s->pixel.kind, s->pixel.threshold, s->poisson_pool, pool_seed, e)) ||
        !(*light = sampler_new(s->light.kind, s->light.threshold, s->poisson_pool, pool_seed + 1, e))) {
        sampler_free(*pix);
        *pix = NULL;
        return -1;
    }
    sampler_set_domain(*pix, s->poisson_domain);
    sampler_set_domain(*light, s->poisson_domain);
    return 0;
}
