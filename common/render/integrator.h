/* integrator: the light transport estimators a job may pick, one row each (name, the text it adds
   to a render's hash, whether russian roulette is on by default). */
#ifndef INTEGRATOR_H
#define INTEGRATOR_H

enum integrator {
    INTEGRATOR_MIXTURE, /* the books': one direction per bounce from a BSDF / light mixture */
    INTEGRATOR_NEE      /* next-event estimation with MIS at every diffuse or medium vertex */
};

struct integrator_traits {
    const char *name;     /* the job key integrator:'s value, the sidecar's */
    const char *hash_tag; /* what it adds to a render's canonical text ("" keeps the old hashes) */
    int roulette;         /* russian_roulette when the job does not say */
};

/* The row of i (the first row for a value outside the enum). */
const struct integrator_traits *integrator_traits(enum integrator i);
/* Every integrator's name in enum order, then NULL (a job's integrator: is read through them). */
const char *const *integrator_names(void);

#endif
