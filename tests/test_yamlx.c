/* Tests for yamlx: merge keys expanded as YAML 1.1 says, quoted scalars refused as numbers and
   booleans, errors at the right line:col. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "scenefile/yamlx.h"
#include "scenefile/yget.h"

static char path[64];

/* Load text as a document from a temporary file; 0 or -1 (with e). */
static int load_text(struct ydoc *d, const char *text, struct err *e)
{
    snprintf(path, sizeof path, "/tmp/test_yamlx_XXXXXX");
    int fd = mkstemp(path);
    if (fd < 0)
        return -1;
    FILE *f = fdopen(fd, "w");
    fputs(text, f);
    fclose(f);
    int rc = ydoc_load(d, path, e);
    unlink(path);
    return rc;
}

/* The scalar under key in the root mapping, or NULL. */
static const char *root_value(struct ydoc *d, const char *key)
{
    return yscalar(ymap_get(d, ydoc_root(d), key));
}

/* Whether scalar s (possibly NULL) is want. */
static int eq(const char *s, const char *want)
{
    return s && !strcmp(s, want);
}

static int pairs(struct ydoc *d, yaml_node_t *m)
{
    yaml_node_t *k, *v;
    int n = 0;
    while (ymap_pair(d, m, n, &k, &v))
        n++;
    return n;
}

static void test_merge(void)
{
    struct ydoc d;
    struct err e;
    static const char *const keys[] = {"a", "b", "c", NULL};
    /* the mapping's own keys win over the merged ones, wherever the << stands */
    CHECK(load_text(&d, "defaults: &d {a: 1, b: 2}\nm: {b: 9, <<: *d, c: 3}\n", &e) == 0);
    yaml_node_t *m = ymap_get(&d, ydoc_root(&d), "m");
    CHECK(pairs(&d, m) == 3);
    CHECK(ymap_check(&d, m, keys, "m", &e) == 0);
    CHECK(eq(yscalar(ymap_get(&d, m, "a")), "1"));
    CHECK(eq(yscalar(ymap_get(&d, m, "b")), "9"));
    CHECK(eq(yscalar(ymap_get(&d, m, "c")), "3"));
    CHECK(ymap_get(&d, m, "<<") == NULL);
    ydoc_free(&d);

    /* a list of sources: the earlier ones win */
    CHECK(load_text(&d, "<<: [{a: 1}, {a: 2, b: 2}]\nc: 3\n", &e) == 0);
    CHECK(eq(root_value(&d, "a"), "1") && eq(root_value(&d, "b"), "2"));
    CHECK(pairs(&d, ydoc_root(&d)) == 3);
    ydoc_free(&d);

    /* a source's own merge keys are expanded first */
    CHECK(load_text(&d, "x: &x {a: 1}\ny: &y {<<: *x, b: 2}\nz: {<<: *y}\n", &e) == 0);
    yaml_node_t *z = ymap_get(&d, ydoc_root(&d), "z");
    CHECK(pairs(&d, z) == 2 && eq(yscalar(ymap_get(&d, z, "a")), "1"));
    ydoc_free(&d);

    /* a quoted "<<" is an ordinary key */
    CHECK(load_text(&d, "\"<<\": {a: 1}\n", &e) == 0);
    CHECK(ymap_get(&d, ydoc_root(&d), "<<") != NULL && ymap_get(&d, ydoc_root(&d), "a") == NULL);
    ydoc_free(&d);

    /* a merge of anything but mappings is an error at the value */
    CHECK(load_text(&d, "a: 1\n<<: 5\n", &e) < 0);
    CHECK(e.line == 2 && e.col == 5 && strstr(e.msg, "<<: a merge key takes a mapping"));
    CHECK(load_text(&d, "<<: [{a: 1}, [2]]\n", &e) < 0);
    CHECK(e.line == 1 && e.col == 14 && strstr(e.msg, "merge key"));

    /* two << keys in one mapping are a duplicate key, as any other (one of them used to win
       silently: the first here, the last in PyYAML) */
    CHECK(load_text(&d, "a: 1\n<<: {b: 1}\n<<: {b: 2}\n", &e) < 0);
    CHECK(e.line == 3 && e.col == 1 && strstr(e.msg, "<<: duplicate key") && strstr(e.msg, "line 2"));
}

/* A merge into a mapping scans its keys for each entry copied: a huge one is refused, not left
   to run for minutes (20000 keys: 2e8 comparisons, over the bound). */
static void test_merge_bound(void)
{
    size_t cap = 20000 * 16 + 64, len = 0;
    char *text = malloc(cap);
    struct ydoc d;
    struct err e;
    if (!text)
        return;
    len += (size_t)snprintf(text + len, cap - len, "a: &a {");
    for (int i = 0; i < 20000; i++)
        len += (size_t)snprintf(text + len, cap - len, "%sk%d: 1", i ? ", " : "", i);
    snprintf(text + len, cap - len, "}\nb: {<<: *a}\n");
    CHECK(load_text(&d, text, &e) < 0 && strstr(e.msg, "too large"));
    free(text);
}

static void test_quoted(void)
{
    struct ydoc d;
    struct err e;
    double x;
    long n;
    int b;
    CHECK(load_text(&d, "t: \"5\"\nu: '5'\nv: 5\nw: \"true\"\nz: true\n", &e) == 0);
    yaml_node_t *root = ydoc_root(&d);
    CHECK(yget_double(&d, ymap_get(&d, root, "t"), "t", &x, &e) < 0);
    CHECK(e.line == 1 && e.col == 4 && strstr(e.msg, "quoted"));
    CHECK(yget_long(&d, ymap_get(&d, root, "u"), "u", 0, 9, &n, &e) < 0 && strstr(e.msg, "quoted"));
    CHECK(yget_double(&d, ymap_get(&d, root, "v"), "v", &x, &e) == 0 && x == 5);
    CHECK(yget_bool(&d, ymap_get(&d, root, "w"), "w", &b, &e) < 0 && e.line == 4);
    CHECK(yget_bool(&d, ymap_get(&d, root, "z"), "z", &b, &e) == 0 && b == 1);
    ydoc_free(&d);
    /* YAML 1.2's core schema booleans, and not 1.1's yes/no */
    CHECK(load_text(&d, "a: True\nb: FALSE\nc: False\nd: yes\n", &e) == 0);
    root = ydoc_root(&d);
    CHECK(yget_bool(&d, ymap_get(&d, root, "a"), "a", &b, &e) == 0 && b == 1);
    CHECK(yget_bool(&d, ymap_get(&d, root, "b"), "b", &b, &e) == 0 && b == 0);
    CHECK(yget_bool(&d, ymap_get(&d, root, "c"), "c", &b, &e) == 0 && b == 0);
    CHECK(yget_bool(&d, ymap_get(&d, root, "d"), "d", &b, &e) < 0 && strstr(e.msg, "true or false"));
    ydoc_free(&d);
}

/* A null on a key reads as the key absent (its default); ymap_check still sees the key, and a
   required one says "needs a value" at the null. */
static void test_null(void)
{
    struct ydoc d;
    struct err e;
    static const char *const keys[] = {"a", "b", "c", "d", "f", "g", "h", NULL};
    CHECK(load_text(&d, "a: ~\nb:\nc: null\nd: \"~\"\nf: !!null x\ng: NULL\nh: 1\n", &e) == 0);
    yaml_node_t *root = ydoc_root(&d);
    CHECK(ymap_check(&d, root, keys, "m", &e) == 0);
    CHECK(!ymap_get(&d, root, "a") && !ymap_get(&d, root, "b") && !ymap_get(&d, root, "c"));
    CHECK(eq(root_value(&d, "d"), "~")); /* quoted: a string */
    CHECK(!ymap_get(&d, root, "f") && !ymap_get(&d, root, "g") && eq(root_value(&d, "h"), "1"));
    CHECK(ymap_get_raw(&d, root, "a") != NULL);
    CHECK(pairs(&d, root) == 2); /* d and h */
    CHECK(ymap_missing(&d, root, "c", &e, "c: missing") < 0 && e.line == 3 && e.col == 4 &&
          strstr(e.msg, "c: needs a value"));
    CHECK(ymap_missing(&d, root, "z", &e, "z: missing") < 0 && e.line == 1 && !strcmp(e.msg, "z: missing"));
    ydoc_free(&d);
    static const char *const one[] = {"a", NULL};
    CHECK(load_text(&d, "a: ~\nb: ~\n", &e) == 0);
    CHECK(ymap_check(&d, ydoc_root(&d), one, "m", &e) < 0 && strstr(e.msg, "b: unknown key"));
    ydoc_free(&d);
}

/* An unknown key's "did you mean": a synonym's key where it is allowed, ahead of a near miss;
   else the near miss; else none. */
static const char *suggestion(const char *text, const char *const *keys)
{
    static char msg[512];
    struct ydoc d;
    struct err e;
    msg[0] = 0;
    if (load_text(&d, text, &e) == 0 && ymap_check(&d, ydoc_root(&d), keys, "m", &e) < 0)
        snprintf(msg, sizeof msg, "%s", e.msg);
    ydoc_free(&d);
    const char *q = strstr(msg, "(did you mean \"");
    return q ? q + 15 : "";
}

static int starts(const char *s, const char *prefix)
{
    return !strncmp(s, prefix, strlen(prefix));
}

static void test_synonyms(void)
{
    static const char *const job[] = {"sampler", "threshold", NULL}, *const mat[] = {"type", "albedo", NULL},
                             *const tex[] = {"type", "scale", NULL};
    CHECK(starts(suggestion("samples: 4\n", job), "threshold\"? the samples per pixel"));
    CHECK(starts(suggestion("SPP: 4\n", job), "threshold\"?"));
    CHECK(starts(suggestion("sampler: x\nsamplr: 4\n", job), "sampler\"?)"));
    CHECK(starts(suggestion("colour: [1, 1, 1]\n", mat), "albedo\"?)"));
    CHECK(!strcmp(suggestion("colour: [1, 1, 1]\n", tex), "")); /* albedo is not a key there */
}

int main(void)
{
    test_null();
    test_synonyms();
    test_merge();
    test_merge_bound();
    test_quoted();
    return check_report("test_yamlx");
}
