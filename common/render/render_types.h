/* render_types: what a render is asked (its settings) and what it counted (its stats), the types
   render.h's callers and the renderer's own parts (render_internal.h) share. */
#ifndef RENDER_TYPES_H
#define RENDER_TYPES_H

#include <stdint.h>

#include "integrator.h"

struct render_settings {
    int width, height;
    int max_depth;
    uint64_t seed;
    int light_sampling_off;     /* 1: scatter by the material alone (cosine / phase); lights still emit */
    enum integrator integrator; /* integrator.h: the books' mixture, or next-event estimation with MIS */
    int dims_all; /* 1: every 2D decision of a path from the pixel sampler's sets (sample/padding.h) */
    int russian_roulette; /* 1: a path may end after its second scatter (render_path.h's path_survives) */
};

/* Counters one process accumulates; summed by the parent. */
struct render_stats {
    uint64_t pixels;
    uint64_t samples;     /* camera samples = camera rays */
    uint64_t rays;        /* rays traced: path segments (camera rays included) and shadow rays */
    uint64_t shadow_rays; /* of rays, next-event estimation's shadow rays */
    uint64_t light_sets;  /* light point sets drawn */
    /* Work counts: the same on every machine, run, process count and split. Points of the pixel
       sets drawn (a pixel's whole set, traced or not); light points taken from the light
       sampler's sets; sampler_dims: all's decisions taken from the padded sets, and those sets
       drawn (one per pixel and slot a sample reached). */
    uint64_t pixel_points, light_points, padded_points, padded_sets;
    uint64_t nonfinite; /* samples whose estimate was NaN or infinite, counted as zero */
    uint32_t spp_min, spp_max;
    /* One pixel in SAMPLER_TIME_EVERY is timed whole, and every point-set draw in it: their
       monotonic nanoseconds. Draws lie inside their pixel, so draw_ns <= pixel_ns always. */
    uint64_t timed_pixel_ns, timed_draw_ns;
    double sampler_s; /* estimated CPU seconds spent drawing point sets (render_stats_finish) */
};

#endif
