/* job_limits: refusing jobs that would run for ever or exhaust memory, before anything is forked. */
#ifndef JOB_LIMITS_H
#define JOB_LIMITS_H

#include <stddef.h>
#include <stdint.h>

#include "job.h"

/* Most camera samples one job may ask for (width x height x samples per set). */
#define LIMITS_MAX_JOB_SAMPLES 100000000000.0

/* Most points one Poisson pool may hold (poisson_pool x the largest set, per sampler). */
#define LIMITS_MAX_POOL_POINTS 33554432.0

/* Refuse a job that would draw too much: width x height x (largest pixel set), or of fresh Poisson
   light sets per pixel and light, over LIMITS_MAX_JOB_SAMPLES; a Poisson pool of poisson_pool x
   (largest set) over LIMITS_MAX_POOL_POINTS. 0, or -1 with e at the key to change. */
int job_limits_samples(const struct job *j, int width, int height, struct err *e);

/* Refuse a framebuffer (and friends) of `bytes` when it exceeds half the memory available now
   (MemAvailable in /proc/meminfo; no check where that is unknown). 0 or -1 with e filled. */
int job_limits_memory(const char *what, size_t bytes, struct err *e);

#endif
