/* test_verdict_look: the bluest variant at equal relMSE on constructed figures: a bluer variant of
   equal relMSE wins, a bluer one of worse relMSE is left out, equal looks are inconclusive, no
   error_lowfreq gives no comparison; verdict.json and the plot carry it. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "verdict_fixture.h"
#include "study/judge/verdict.h"
#include "study/judge/verdict_look.h"
#include "study/present/report_look.h"
#include "study/present/verdict_out.h"

#define NV 3
#define NP 2
#define NS 8
_Static_assert(NV <= VF_MAX_V && NP <= VF_MAX_P && NS <= VF_MAX_S, "verdict_fixture.h too small");

/* relMSE = k[v] / spp x a seed's factor; error_lowfreq = look[v] x another (spread about 6%). */
static void fake_init(struct verdict_fixture *x, const double *k, const double *look)
{
    static const char *const names[NV] = {"sobol", "zsobol", "random"};
    static const double spp[NP] = {4, 16};
    verdict_fixture_init(x, "look", NV, NP, NS, 4096);
    x->f.lowfreq = x->lowfreq;
    x->points[0] = "threshold 50", x->points[1] = "threshold 25";
    for (int v = 0; v < NV; v++) {
        x->variants[v] = names[v], x->samplers[v] = names[v];
        for (int p = 0; p < NP; p++) {
            x->rel_of_mean[v * NP + p] = x->bias_rel[v * NP + p] = NAN;
            for (int s = 0; s < NS; s++) {
                int i = verdict_at(&x->f, v, p, s);
                x->spp[i] = spp[p], x->cpu[i] = spp[p] * 1e-3, x->radiance[i] = 1;
                x->rel[i] = k[v] / spp[p] * (0.9 + 0.2 * ((s * 5 + v) % NS) / NS);
                x->lowfreq[i] = look[v] * (0.9 + 0.2 * ((s * 3 + 1) % NS) / NS);
            }
        }
    }
}

static void test_bluest(void)
{
    struct verdict_fixture x;
    struct verdict_scene s;
    struct err e = {0};
    const double k[NV] = {1, 1, 4}, look[NV] = {1.0, 0.7, 0.3};
    fake_init(&x, k, look);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK_NEAR(s.look.at, 4, 1e-12);
    CHECK(s.look.point[0] == 0 && s.look.point[2] == 0);
    /* random is bluest but its relMSE is 4x: not at equal relMSE, left out */
    CHECK(s.look.by_look.n == 2);
    CHECK(s.look.by_look.status == VERDICT_CLEAR && s.look.by_look.e[0].variant == 1);
    CHECK_NEAR(s.look.mean[1 * NP + 0], 0.7 * (0.9 + 0.2 * 3.5 / NS), 1e-9);
    CHECK(s.look.se[1 * NP + 0] > 0 && s.look.se[1 * NP + 0] < 0.05);
    CHECK_NEAR(s.look.rel[2 * NP + 1], 4.0 / 16 * exp(0), 0.05);
    int said = 0;
    for (int i = 0; i < s.n_sentences; i++)
        said |= strstr(s.sentences[i], "bluest: zsobol.") != NULL;
    CHECK(said);
    struct verdict_study st = {.name = "look", .n_scenes = 1, .scenes = &s};
    char *json = verdict_json_text("job", &st, 1, NULL), *svg = report_look_svg(&st, REPORT_LOOK_LOWFREQ);
    CHECK(json && strstr(json, "\"error_look\"") && strstr(json, "\"bluest\"") &&
          strstr(json, "\"winner\": \"zsobol\""));
    CHECK(svg && strstr(svg, "board: how the error looks") && strstr(svg, "zsobol"));
    free(json), free(svg);
    verdict_scene_free(&s);

    const double same[NV] = {0.8, 0.8, 0.8}; /* equal looks: no bluest */
    fake_init(&x, k, same);
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.look.by_look.n == 2 && s.look.by_look.status == VERDICT_INCONCLUSIVE);
    verdict_scene_free(&s);

    fake_init(&x, k, look);
    x.f.lowfreq = NULL; /* not measured: no comparison, no sentence */
    CHECK(verdict_scene_compute(&x.f, &s, &e) == 0);
    CHECK(s.look.by_look.n == 0 && isnan(s.look.mean[0]));
    for (int i = 0; i < s.n_sentences; i++)
        CHECK(strstr(s.sentences[i], "bluest") == NULL);
    verdict_scene_free(&s);
}

int main(void)
{
    test_bluest();
    return check_report("test_verdict_look");
}
