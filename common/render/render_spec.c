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

static const char *const *dims_names(void)
{
    static const char *const names[] = {"pixel_light", "all", NULL};
    return names;
}

static const char *const *roulette_names(void)
{
    static const char *const names[] = {"off", "on", NULL};
    return names;
}

#define AT(field) offsetof(struct render_spec, field)
/* key, type, field, lo, hi, names, default, changes pixels, label, summary.csv's place. In the order
   the sidecar and summary.csv write them; a new setting is a row at the end (and a field in struct
   render_spec). */
static const struct render_spec_row rows[] = {
    {"width", RS_INT, AT(width), 1, IMAGE_MAX_SIDE, NULL, 300, 1, "width", 0},
    {"height", RS_INT, AT(height), 1, IMAGE_MAX_SIDE, NULL, 0, 1, "height", 0},
    {"sampler", RS_SAMPLER, AT(pixel.kind), 0, 0, NULL, SAMPLER_RANDOM, 1, "sampler", 0},
    {"threshold", RS_THRESHOLD, AT(pixel.threshold), 0, 100, NULL, 5, 1, "threshold", 1},
    {"light_sampler", RS_SAMPLER, AT(light.kind), 0, 0, NULL, SAMPLER_RANDOM, 1, "light sampler", 0},
    {"light_threshold", RS_THRESHOLD, AT(light.threshold), 0, 100, NULL, 5, 1, "light threshold", 1},
    {"light_sampling", RS_BOOL, AT(light_sampling), 0, 1, NULL, 1, 1, "light sampling", 0},
    {"integrator", RS_CHOICE, AT(integrator), 0, 0, integrator_names, INTEGRATOR_MIXTURE, 1, "integrator", 0},
    {"sampler_dims", RS_CHOICE, AT(dims_all), 0, 0, dims_names, 0, 1, "sampler dims", 0},
    {"russian_roulette", RS_CHOICE, AT(roulette), 0, 0, roulette_names, -1, 1, "russian roulette", 0},
    {"poisson_pool", RS_INT, AT(poisson_pool), 0, 65536, NULL, 0, 1, "poisson pool", 0},
    {"poisson_domain", RS_CHOICE, AT(poisson_domain), 0, 0, poisson_domain_names, POISSON_TORUS, 1, "poisson domain", 0},
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

uint64_t render_spec_get(const struct render_spec *s, const struct render_spec_row *r)
{
    const char *p = (const char *)s + r->offset;
    return r->type == RS_U64 ? *(const uint64_t *)(const void *)p : (uint64_t)(int64_t) * (const int *)(const void *)p;
}

double render_spec_get_threshold(const struct render_spec *s, const struct render_spec_row *r)
{
    return *(const double *)(const void *)((const char *)s + r->offset);
}

void render_spec_put(struct render_spec *s, const struct render_spec_row *r, uint64_t v)
{
    char *p = (char *)s + r->offset;
    if (r->type == RS_U64)
        *(uint64_t *)(void *)p = v;
    else
        *(int *)(void *)p = (int)(int64_t)v;
}

void render_spec_put_threshold(struct render_spec *s, const struct render_spec_row *r, double t)
{
    *(double *)(void *)((char *)s + r->offset) = t;
}

void render_spec_defaults(struct render_spec *s)
{
    memset(s, 0, sizeof *s);
    for (int i = 0; i < N_ROWS; i++)
        if (rows[i].type == RS_THRESHOLD)
            render_spec_put_threshold(s, &rows[i], rows[i].default_value);
        else
            render_spec_put(s, &rows[i], (uint64_t)(int64_t)rows[i].default_value);
}

int render_spec_in_range(const struct render_spec_row *r, double v)
{
    if (r->type == RS_THRESHOLD)
        return sampler_threshold_valid(v);
    return v >= (double)r->lo && v <= (double)r->hi;
}

int render_spec_roulette(const struct render_spec *s)
{
    return s->roulette < 0 ? integrator_traits(s->integrator)->roulette : s->roulette;
}

const char *render_spec_text(const struct render_spec *s, const struct render_spec_row *r, char *buf, size_t n)
{
    const uint64_t v = render_spec_get(s, r);
    switch (r->type) {
    case RS_THRESHOLD:
        for (int digits = 6; digits <= 17; digits += digits == 6 ? 9 : 1) { /* %g when it reads back */
            snprintf(buf, n, "%.*g", digits, render_spec_get_threshold(s, r));
            if (strtod(buf, NULL) == render_spec_get_threshold(s, r))
                break;
        }
        break;
    case RS_SAMPLER:
        snprintf(buf, n, "%s", sampler_kind_name((enum sampler_kind)v));
        break;
    case RS_CHOICE: /* roulette's -1 is resolved: the text says what the render does */
        snprintf(buf, n, "%s", r->names()[r->offset == AT(roulette) ? render_spec_roulette(s) : (int)v]);
        break;
    case RS_BOOL:
        snprintf(buf, n, "%s", v ? "true" : "false");
        break;
    case RS_U64:
        snprintf(buf, n, "%llu", (unsigned long long)v);
        break;
    default:
        snprintf(buf, n, "%d", (int)(int64_t)v);
    }
    return buf;
}

int render_spec_set_text(struct render_spec *s, const struct render_spec_row *r, const char *text)
{
    char *end;
    if (r->type == RS_THRESHOLD) {
        double t = strtod(text, &end);
        if (!*text || *end || !render_spec_in_range(r, t))
            return -1;
        render_spec_put_threshold(s, r, t);
        return 0;
    }
    if (r->type == RS_SAMPLER) {
        enum sampler_kind k;
        if (sampler_kind_parse(text, &k) < 0)
            return -1;
        render_spec_put(s, r, (uint64_t)k);
        return 0;
    }
    if (r->type == RS_CHOICE || r->type == RS_BOOL) {
        const char *const bools[] = {"false", "true", NULL};
        const char *const *names = r->type == RS_BOOL ? bools : r->names();
        for (int i = 0; names[i]; i++)
            if (!strcmp(text, names[i])) {
                render_spec_put(s, r, (uint64_t)i);
                return 0;
            }
        return -1;
    }
    errno = 0;
    if (r->type == RS_U64) { /* any seed a render had: a reference half's own is mixed to 64 bits */
        unsigned long long u = strtoull(text, &end, 10);
        if (strspn(text, "0123456789") != strlen(text) || !*text || errno)
            return -1;
        render_spec_put(s, r, (uint64_t)u);
        return 0;
    }
    long v = strtol(text, &end, 10);
    if (!*text || *end || errno || !render_spec_in_range(r, (double)v))
        return -1;
    render_spec_put(s, r, (uint64_t)(int64_t)v);
    return 0;
}

const char *render_spec_expected(const struct render_spec_row *r, char *buf, size_t n)
{
    if (r->type == RS_INT || r->type == RS_U64)
        snprintf(buf, n, "a whole number in [%ld, %ld]", r->lo, r->hi);
    else if (r->type == RS_THRESHOLD)
        snprintf(buf, n, "a number in (0, 100]");
    else if (r->type == RS_BOOL)
        snprintf(buf, n, "true or false");
    else {
        const char *const *names = r->type == RS_SAMPLER ? sampler_kind_names() : r->names();
        size_t used = (size_t)snprintf(buf, n, "one of");
        for (int i = 0; names[i] && used < n; i++)
            used += (size_t)snprintf(buf + used, n - used, "%s %s", i ? "," : "", names[i]);
    }
    return buf;
}

void render_spec_json(const struct render_spec *s, struct json *js)
{
    char text[64];
    for (int i = 0; i < N_ROWS; i++) {
        const struct render_spec_row *r = &rows[i];
        render_spec_text(s, r, text, sizeof text);
        if (r->type == RS_SAMPLER || r->type == RS_CHOICE)
            json_string(js, r->key, text);
        else if (r->type == RS_BOOL)
            json_bool(js, r->key, (int)render_spec_get(s, r));
        else
            json_number_text(js, r->key, text);
    }
}

void render_spec_csv_header(struct sbuf *b, int front)
{
    for (int i = 0; i < N_ROWS; i++)
        if (rows[i].csv_front == front)
            sbuf_printf(b, "%s,", rows[i].key);
}

void render_spec_csv_row(const struct render_spec *s, int front, struct sbuf *b)
{
    char text[64];
    for (int i = 0; i < N_ROWS; i++)
        if (rows[i].csv_front == front)
            sbuf_printf(b, "%s,", render_spec_text(s, &rows[i], text, sizeof text));
}

int render_spec_from_fields(struct render_spec *s, const char *const *names, const char *const *values,
                            int n, const char *file, int line, struct err *e)
{
    render_spec_defaults(s);
    for (int i = 0; i < N_ROWS; i++) {
        int k = 0;
        while (k < n && strcmp(names[k], rows[i].key))
            k++;
        if (k == n)
            return err_set(e, file, line, 0, "%s: no such column", rows[i].key);
        char want[160];
        if (render_spec_set_text(s, &rows[i], values[k]) < 0)
            return err_set(e, file, line, 0, "%s: expected %s, got \"%.40s\"", rows[i].key,
                           render_spec_expected(&rows[i], want, sizeof want), values[k]);
    }
    return 0;
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
        snprintf(buf, n, " %s %s%s", sampler_kind_name(SAMPLER_POISSON), poisson_domain_name(s->poisson_domain), pad);
    return buf;
}

int render_spec_key_text(const struct render_spec *s, const char *middle, char *buf, size_t n)
{
    char tag[64], text[64];
    int len = snprintf(buf, n, "%dx%d %s %.17g %s %.17g depth %d seed %llu pool %d lights %d%s worker %s%s%s%s%s",
                       s->width, s->height, sampler_kind_name(s->pixel.kind), s->pixel.threshold,
                       sampler_kind_name(s->light.kind), s->light.threshold, s->max_depth,
                       (unsigned long long)s->seed, s->poisson_pool, s->light_sampling, middle, WORKER_VERSION,
                       integrator_traits(s->integrator)->hash_tag, s->dims_all ? " dims all" : "",
                       sets_tag(s, tag, sizeof tag), render_spec_roulette(s) ? " roulette" : "");
    struct render_spec dflt;
    render_spec_defaults(&dflt);
    for (int i = KEY_TEXT_ROWS; i < N_ROWS && len >= 0 && (size_t)len < n; i++) {
        if (render_spec_get(s, &rows[i]) != render_spec_get(&dflt, &rows[i]))
            len += snprintf(buf + len, n - (size_t)len, " %s %s", rows[i].key,
                            render_spec_text(s, &rows[i], text, sizeof text));
    }
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
