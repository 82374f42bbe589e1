/* clock: a clock's reading in seconds (monotonic for elapsed times, realtime to compare with
   file times, a CPU clock for CPU time). */
#ifndef CLOCK_H
#define CLOCK_H

#include <time.h>

/* Clock id's time now, in seconds. */
static inline double clock_s(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

#endif
