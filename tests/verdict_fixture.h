/* verdict_fixture: verdict figures built by hand for the verdict's tests (test_verdict.c,
   test_verdict_look.c): room for up to VF_MAX_V variants, VF_MAX_P sweep points and VF_MAX_S
   seeds, wired into one struct verdict_figures whose figures the test then fills. */
#ifndef VERDICT_FIXTURE_H
#define VERDICT_FIXTURE_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "study/judge/verdict.h"

#define VF_MAX_V 4
#define VF_MAX_P 3
#define VF_MAX_S 8
#define VF_MAX_N (VF_MAX_V * VF_MAX_P * VF_MAX_S)

struct verdict_fixture {
    struct verdict_figures f;
    const char *variants[VF_MAX_V], *samplers[VF_MAX_V], *points[VF_MAX_P];
    int pools[VF_MAX_V];
    double spp[VF_MAX_N], cpu[VF_MAX_N], rel[VF_MAX_N], share[VF_MAX_N], lowfreq[VF_MAX_N],
        radiance[VF_MAX_N];
    double rel_of_mean[VF_MAX_V * VF_MAX_P], bias_rel[VF_MAX_V * VF_MAX_P]; /* per (variant, point) */
    uint64_t nonfinite[VF_MAX_N];
};

/* x zeroed, sized nv x np x ns (each within its VF_MAX_) for study `study` of scene "board", its
   figures wired into x->f; the reference of ref_spp samples per pixel, its relMSE and radiance
   unknown; no error_lowfreq (x->f.lowfreq = x->lowfreq measures it). */
static inline void verdict_fixture_init(struct verdict_fixture *x, const char *study, int nv, int np, int ns,
                                        double ref_spp)
{
    memset(x, 0, sizeof *x);
    x->f =
        (struct verdict_figures){.study = study,
                                 .scene = "board",
                                 .n_variants = nv,
                                 .n_points = np,
                                 .n_seeds = ns,
                                 .variants = x->variants,
                                 .samplers = x->samplers,
                                 .pools = x->pools,
                                 .points = x->points,
                                 .spp = x->spp,
                                 .cpu_s = x->cpu,
                                 .relmse = x->rel,
                                 .sampler_share = x->share,
                                 .nonfinite = x->nonfinite,
                                 .rel_of_mean = x->rel_of_mean,
                                 .bias_rel = x->bias_rel,
                                 .radiance = x->radiance,
                                 .ref = {.spp = ref_spp, .relmse = NAN, .radiance = NAN, .radiance_se = NAN}};
}

#endif
