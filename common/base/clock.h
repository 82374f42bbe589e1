/* clock: a clock's reading in seconds or nanoseconds (monotonic for elapsed times, realtime to
   compare with file times, a CPU clock for CPU time). */
#ifndef CLOCK_H
#define CLOCK_H

#include <stdint.h>
#include <time.h>

/* Clock id's time now, in seconds. */
static inline double clock_s(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* Clock id's time now, in whole nanoseconds (intervals that must add up exactly: the sampler's
   timing). */
static inline uint64_t clock_ns(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

#endif
