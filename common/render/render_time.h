/* render_time: the clock of the sidecar's sampler_s, and which pixels it times. Internal to
   common/render/; static, as each of render.c and render_lanes.c includes it. */
#ifndef RENDER_TIME_H
#define RENDER_TIME_H

#include <stdint.h>

#include "base/clock.h"

/* The sidecar's sampler_s: one pixel in SAMPLER_TIME_EVERY (by st->pixels) is timed whole, and
   every point-set draw inside it, in integer nanoseconds of one monotonic clock; the draws' share
   of those pixels' time, times the process's CPU time, estimates the CPU time spent drawing
   (render_stats_finish). The draws are intervals inside their pixel's, so the share cannot
   exceed 1. Timing one draw in eight and counting it for the next seven made the share 2.1 and
   more: a time slice lost in a timed draw counted eight times, and on a busy machine a wall
   clock runs on while a process waits. Timing every draw cost two clock reads per set, ~0.8% of
   final's time, more than drawing a jitter set. */
#define SAMPLER_TIME_EVERY 8
static inline int sampler_timed(uint64_t pixels)
{
    return pixels % SAMPLER_TIME_EVERY == 0;
}

#endif
