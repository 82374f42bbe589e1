/* test_errspec_look: the pooled error spectrum's look. A sine grating over noise has a peak no
   noise gives (peak_p tiny), streaks along rows are strongly anisotropic; white and blue noise have neither;
   blue noise's radial power rises with frequency, white's is flat. */
#include "image/errspec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/rng.h"
#include "check.h"

#define W 64
#define N_IMAGES 8

enum kind { WHITE, BLUE, GRATING, STREAKS };

/* One error field of the kind (periodic, W x W) into d. */
static void field(enum kind k, struct rng *r, double *d)
{
    double n[W * W];
    for (int i = 0; i < W * W; i++)
        n[i] = rng_uniform(r) - 0.5;
    for (int y = 0; y < W; y++)
        for (int x = 0; x < W; x++) {
            double v = n[y * W + x];
            if (k == BLUE) { /* minus the 3x3 neighbourhood's mean: a high-pass, isotropic enough */
                double s = 0;
                for (int dy = -1; dy <= 1; dy++)
                    for (int dx = -1; dx <= 1; dx++)
                        s += n[((y + dy + W) % W) * W + (x + dx + W) % W];
                v -= s / 9;
            }
            if (k == STREAKS) /* each pixel's noise smeared over its row's neighbours: streaks */
                v += n[y * W + (x + 1) % W] + n[y * W + (x + W - 1) % W];
            if (k == GRATING) /* a grating of 5 cycles across, a tenth of the noise's amplitude */
                v += 0.05 * sin(2 * M_PI * 5 * x / W);
            d[y * W + x] = v;
        }
}

static struct errspec_look look_of(enum kind k, uint64_t seed)
{
    struct rgbf ref = {W, W, malloc(sizeof(float) * 3 * W * W)},
                img = {W, W, malloc(sizeof(float) * 3 * W * W)};
    double *acc = calloc((size_t)ERRSPEC_MAX_SIDE * ERRSPEC_MAX_SIDE, sizeof *acc), d[W * W];
    struct rng rng;
    struct err e;
    int w = 0, h = 0;
    rng_seed(&rng, seed, 7);
    for (int n = 0; n < N_IMAGES; n++) {
        field(k, &rng, d);
        for (int i = 0; i < W * W; i++)
            for (int c = 0; c < 3; c++)
                ref.px[3 * i + c] = 0.5f, img.px[3 * i + c] = (float)(0.5 + d[i]);
        CHECK(errspec_power_add(&ref, &img, acc, &w, &h, &e) == 0);
    }
    CHECK(w == W && h == W);
    struct errspec_look l;
    errspec_look_of(acc, w, h, N_IMAGES, &l);
    free(acc), free(ref.px), free(img.px);
    return l;
}

int main(void)
{
    int white_flagged = 0, blue_flagged = 0;
    for (uint64_t s = 1; s <= 20; s++) {
        struct errspec_look wl = look_of(WHITE, s), bl = look_of(BLUE, s);
        white_flagged += wl.peak_p < ERRSPEC_PEAK_P || wl.anisotropy > ERRSPEC_ANISOTROPY;
        blue_flagged += bl.peak_p < ERRSPEC_PEAK_P || bl.anisotropy > ERRSPEC_ANISOTROPY;
        if (s == 1) {
            printf("white: peak %.2f (p %.3g), anisotropy %.2f, rings 2 %.2f 15 %.2f\n", wl.peak, wl.peak_p,
                   wl.anisotropy, wl.ring[2], wl.ring[15]);
            printf("blue: peak %.2f (p %.3g), anisotropy %.2f, rings 2 %.2f 15 %.2f\n", bl.peak, bl.peak_p,
                   bl.anisotropy, bl.ring[2], bl.ring[15]);
            CHECK(wl.ring[2] > 0.7 && wl.ring[2] < 1.3 && wl.ring[15] > 0.7 && wl.ring[15] < 1.3);
            CHECK(bl.ring[2] < 0.2 && bl.ring[15] > 1.2);
        }
    }
    CHECK(white_flagged == 0 && blue_flagged == 0); /* 20 pooled sets of 8 images each */
    struct errspec_look g = look_of(GRATING, 1);
    printf("grating: peak %.1f (p %.3g), anisotropy %.2f\n", g.peak, g.peak_p, g.anisotropy);
    CHECK(g.peak_p < ERRSPEC_PEAK_P);
    struct errspec_look st = look_of(STREAKS, 1);
    printf("streaks: peak %.1f (p %.3g), anisotropy %.2f\n", st.peak, st.peak_p, st.anisotropy);
    CHECK(st.anisotropy > ERRSPEC_ANISOTROPY);
    return check_report("test_errspec_look");
}
