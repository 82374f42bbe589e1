/* render: the path integrator of RTOW "The Rest of Your Life" driven by our point samplers. */
#ifndef RENDER_H
#define RENDER_H

#include <stddef.h>
#include <stdint.h>

#include "geom/camera.h"
#include "sample/sampler.h"
#include "geom/scene.h"
#include "render_types.h"

struct render_ctx;

/* A per-process render context over sc and cam (both must outlive it). pixel and light are the
   job's samplers (light may be NULL when the scene has no disk or rect light or light
   sampling is off); the context
   allocates every buffer a pixel needs now, so render_pixel allocates nothing. NULL + e on
   no memory. */
struct render_ctx *render_ctx_new(const struct scene *sc, const struct camera *cam,
                                  const struct render_settings *rs, struct sampler *pixel,
                                  struct sampler *light, struct err *e);
void render_ctx_free(struct render_ctx *ctx);

/* Render pixel (x, y) (row 0 at the top) into rgb (linear); its value depends only on the job
   seed, x and y. Adds to st. */
void render_pixel(struct render_ctx *ctx, int x, int y, float rgb[3], struct render_stats *st);

/* render_pixel tracing at most max_paths of the pixel's camera samples, the first ones as
   render_pixel traces them (all when max_paths is SIZE_MAX: render_pixel), into rgb (their mean)
   and st (those traced). Returns how many samples the pixel has. For a cost estimate whose time
   must stay bounded however costly a path is (the dry run's pilot). */
size_t render_pixel_paths(struct render_ctx *ctx, int x, int y, size_t max_paths, float rgb[3],
                          struct render_stats *st);

void render_stats_init(struct render_stats *st);
void render_stats_add(struct render_stats *into, const struct render_stats *from);

/* At the end of a render process: sampler_s = its draw share (the fraction of the timed pixels'
   time spent drawing point sets, in [0, 1], 0 when none was timed) times cpu_s, the process's CPU
   seconds, so that sampler_s never exceeds the CPU time it is a part of. */
void render_stats_finish(struct render_stats *st, double cpu_s);

#endif
