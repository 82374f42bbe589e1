/* job_key: the canonical text of everything that changes a render's pixels, the one text every
   cache key (a compare job's images and its references) is hashed from. */
#ifndef JOB_KEY_H
#define JOB_KEY_H

#include <stddef.h>

#include "job.h"

/* j's settings at width x height as one line: size, samplers and thresholds, depth, seed, pool,
   light sampling, then `middle` (what the caller's key adds: "" or " ref 1"), the worker's
   version, the integrator's tag, sampler_dims, the sets' rules and roulette. Into buf (n bytes);
   returns the text's length (cut to n - 1 when longer). */
int job_key_text(const struct job *j, int width, int height, const char *middle, char *buf, size_t n);

#endif
