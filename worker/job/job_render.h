/* job_render: what a job gives the renderer, in one place: its render settings and its pixel and
   light samplers (their Poisson pools seeded from the image's seed), for the image's render and
   for the study's cost design, which must time the very same work. */
#ifndef JOB_RENDER_H
#define JOB_RENDER_H

#include <stdint.h>

#include "base/err.h"
#include "job.h"
#include "render/render_types.h"
#include "sample/sampler.h"

/* The render settings of j at w x h pixels with the given seed. */
struct render_settings job_render_settings(const struct job *j, int w, int h, uint64_t seed);

/* j's pixel and light samplers for an image of the given seed, domains set. 0, or -1 with e filled
   and both NULL (nothing to free). */
int job_samplers_new(const struct job *j, uint64_t seed, struct sampler **pix, struct sampler **light,
                     struct err *e);

#endif
