/* integrator: the light transport estimators a job may pick, one row each. */
#include "integrator.h"

#include <stddef.h>

/* name, hash tag, roulette by default */
#define INTEGRATOR_ROWS(X) X("mixture", "", 0) X("nee", " nee", 1)
#define AS_ROW(name, tag, roulette) {name, tag, roulette},
#define AS_NAME(name, tag, roulette) name,
static const struct integrator_traits rows[] = {INTEGRATOR_ROWS(AS_ROW)};
#define COUNT ((int)(sizeof rows / sizeof rows[0]))
_Static_assert(COUNT == INTEGRATOR_NEE + 1, "a row per integrator");
static const char *const names[] = {INTEGRATOR_ROWS(AS_NAME) NULL};

const struct integrator_traits *integrator_traits(enum integrator i)
{
    return &rows[(int)i >= 0 && (int)i < COUNT ? (int)i : 0];
}

const char *const *integrator_names(void)
{
    return names;
}
