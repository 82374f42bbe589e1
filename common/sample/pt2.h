/* pt2: a point of the unit square, what every point set is made of (its own header, so that the
   sets' constructions include it and never sampler.h, which calls them). */
#ifndef PT2_H
#define PT2_H

struct pt2 {
    double x, y;
};

#endif
