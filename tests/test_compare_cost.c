/* test_compare_cost: the render order (seed-major, each seed's images shuffled by a seeded
   generator: the same on every run, no variant in a stretch of its own), and cost.csv written and
   read back by name (a folder judged again finds each variant's figures, whatever order its
   summary.csv lists them in); a cost.csv that does not cover the study is not used. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "compare_fixture.h"
#include "base/fileio.h"
#include "study/load/compare_load.h"
#include "study/run/compare_cost.h"

static struct compare_fixture fx;

static struct compare *load(const char *name, const char *yaml)
{
    struct err e;
    struct compare *c = compare_load(compare_fixture_file(&fx, name, yaml), &e);
    CHECK(c != NULL);
    return c;
}

static void test_order(void)
{
    struct compare *c = load("o.yaml", "scenes: [SCENE]\nwidth: 8\nseeds: [1, 2, 3]\n"
                                       "sweep: { threshold: [20, 10] }\nvariants:\n"
                                       "  - { label: a }\n  - { label: b }\n  - { label: c }\n");
    if (!c)
        return;
    int order[64], again[64], per = c->n_items / c->n_seeds, seen[64] = {0}, in_place = 0;
    compare_cost_order(c, order);
    compare_cost_order(c, again);
    CHECK(memcmp(order, again, sizeof(int) * (size_t)c->n_items) == 0); /* seeded: the same each run */
    for (int n = 0; n < c->n_items; n++) {
        const struct compare_item *it = &c->items[order[n]];
        CHECK(it->seed == n / per); /* seed-major */
        seen[order[n]]++;
        in_place += order[n] == compare_index(c, it->scene, it->variant, it->point, it->seed) &&
                    n % per == it->variant * c->n_points + it->point;
    }
    for (int i = 0; i < c->n_items; i++)
        CHECK(seen[i] == 1);          /* every image once */
    CHECK(in_place < c->n_items / 2); /* shuffled, not variant after variant */
    /* no variant renders all its images of a seed in one stretch ahead of the others' */
    int stretch = 1;
    for (int k = 0; k < c->n_seeds; k++)
        for (int n = k * per + 1; n < (k + 1) * per; n++)
            stretch &= c->items[order[n]].variant >= c->items[order[n - 1]].variant;
    CHECK(!stretch);
    compare_free(c);
}

static void test_csv(void)
{
    struct compare *c = load("k.yaml", "name: k\nscenes: [SCENE]\nwidth: 8\nseeds: [1, 2]\n"
                                       "sweep: { threshold: [20, 10] }\nvariants:\n"
                                       "  - { label: a }\n  - { label: b }\n");
    struct compare *d = load("k2.yaml", "name: k\nscenes: [SCENE]\nwidth: 8\nseeds: [1, 2]\n"
                                        "sweep: { threshold: [20, 10] }\nvariants:\n"
                                        "  - { label: b }\n  - { label: a }\n");
    if (!c || !d)
        goto done;
    c->results.n_blocks = 3;
    c->results.cost_s = calloc(2 * 2 * 3, sizeof *c->results.cost_s);
    for (int v = 0; v < 2; v++)
        for (int p = 0; p < 2; p++)
            for (int b = 0; b < 3; b++)
                c->results.cost_s[compare_cost_index(c, 0, v, p, b)] = 0.001 * (1 + v) * (1 + p) * (10 + b);
    struct err e;
    CHECK(fileio_write_text(fx.dir, "cost.csv", compare_cost_csv(c), &e) == 0);
    CHECK(compare_cost_read(d, &d->results, fx.dir) == 0 && d->results.n_blocks == 3);
    if (d->results.n_blocks == 3) /* d lists b first: its figures found by name */
        for (int p = 0; p < 2; p++)
            for (int b = 0; b < 3; b++) {
                CHECK(d->results.cost_s[compare_cost_index(d, 0, 1, p, b)] ==
                      c->results.cost_s[compare_cost_index(c, 0, 0, p, b)]);
                CHECK(d->results.cost_s[compare_cost_index(d, 0, 0, p, b)] ==
                      c->results.cost_s[compare_cost_index(c, 0, 1, p, b)]);
            }
    /* a study with a point cost.csv does not hold: not read (no figure guessed) */
    struct compare *x = load("k3.yaml", "name: k\nscenes: [SCENE]\nwidth: 8\nseeds: [1, 2]\n"
                                        "sweep: { threshold: [20, 10, 5] }\nvariants:\n"
                                        "  - { label: a }\n  - { label: b }\n");
    CHECK(x && compare_cost_read(x, &x->results, fx.dir) < 0 && x->results.n_blocks == 0 &&
          !x->results.cost_s);
    compare_free(x);
    compare_fixture_file(&fx, "cost.csv", "scene,variant,point,block,cpu_s\nnot,a,row,0,1\n");
    free(d->results.cost_s), d->results.cost_s = NULL, d->results.n_blocks = 0;
    CHECK(compare_cost_read(d, &d->results, fx.dir) < 0 && d->results.n_blocks == 0);
done:
    compare_free(c);
    compare_free(d);
}

int main(void)
{
    if (compare_fixture_open(&fx, "test_compare_cost") < 0) {
        fprintf(stderr, "test_compare_cost: no scratch folder\n");
        return 1;
    }
    test_order();
    test_csv();
    compare_fixture_close(&fx);
    return check_report("test_compare_cost");
}
