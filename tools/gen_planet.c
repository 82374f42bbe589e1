/* gen_planet: bakes scenes/textures/planet.png, the cornell scene's planet map, from our
   Perlin noise (fixed seed) and writes it through our PNG writer. `make scenes` runs it. */
#include <stdio.h>
#include <stdlib.h>

#include "base/fileio.h"
#include "image/imgio.h"
#include "geom/perlin.h"

#define PLANET_W 256
#define PLANET_H 128
#define PLANET_SEED 0x706c616e6574ULL

static vec3 mix(vec3 a, vec3 b, double t)
{
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return v3_add(v3_scale(a, 1 - t), v3_scale(b, t));
}

/* Fractal elevation in about [-1, 1]: four octaves of signed noise. */
static double elevation(const struct perlin *pn, vec3 p)
{
    double sum = 0, w = 1;
    for (int i = 0; i < 4; i++) {
        sum += w * perlin_noise(pn, p);
        w *= 0.5;
        p = v3_scale(p, 2);
    }
    return sum;
}

/* The colour at unit direction d: oceans by depth, land by height, ice toward the poles. */
static vec3 planet_color(const struct perlin *pn, vec3 d)
{
    double e = elevation(pn, v3_scale(d, 2.5)) - 0.06;
    double lat = fabs(d.y) + 0.08 * perlin_noise(pn, v3_scale(d, 9));
    vec3 c;
    if (e < 0)
        c = mix(v3(0.10, 0.32, 0.65), v3(0.02, 0.06, 0.28), -e * 5);
    else if (e < 0.2)
        c = mix(v3(0.16, 0.46, 0.14), v3(0.50, 0.42, 0.22), e * 5);
    else
        c = mix(v3(0.50, 0.42, 0.22), v3(0.45, 0.43, 0.42), (e - 0.2) * 5);
    if (lat > 0.88)
        c = v3(0.92, 0.94, 0.97);
    return c;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: gen_planet OUT.png\n");
        return 2;
    }
    struct perlin pn;
    struct rgb8 img;
    struct err e;
    perlin_init(&pn, PLANET_SEED);
    if (image_alloc(&img, PLANET_W, PLANET_H, &e) < 0)
        goto fail;
    for (int j = 0; j < PLANET_H; j++) {
        for (int i = 0; i < PLANET_W; i++) {
            /* Invert shape_uv's sphere map: u = (atan2(-z, x) + pi) / 2pi, v = acos(-y) / pi,
               with row 0 at v = 1. */
            double u = (i + 0.5) / PLANET_W, v = 1 - (j + 0.5) / PLANET_H;
            double theta = v * PI, phi = u * 2 * PI - PI;
            vec3 d = v3(cos(phi) * sin(theta), -cos(theta), -sin(phi) * sin(theta));
            vec3 c = planet_color(&pn, d);
            uint8_t *px = img.px + ((size_t)j * PLANET_W + (size_t)i) * 3;
            px[0] = (uint8_t)(255 * c.x + 0.5);
            px[1] = (uint8_t)(255 * c.y + 0.5);
            px[2] = (uint8_t)(255 * c.z + 0.5);
        }
    }
    if (imgio_write(argv[1], &img, IMG_PNG, &e) < 0)
        goto fail;
    image_free(&img);
    return 0;
fail:
    image_free(&img);
    char buf[1400];
    err_format(&e, buf, sizeof buf);
    fprintf(stderr, "gen_planet: %s\n", buf);
    return 1;
}
