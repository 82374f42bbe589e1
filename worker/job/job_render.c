/* job_render: a job's render settings and samplers, made in one place. */
#include "job_render.h"

#include "base/rng.h"

struct render_settings job_render_settings(const struct job *j, int w, int h, uint64_t seed)
{
    return (struct render_settings){
        w, h, j->max_depth, seed, !j->light_sampling, j->integrator, j->dims_all, job_roulette(j)};
}

int job_samplers_new(const struct job *j, uint64_t seed, struct sampler **pix, struct sampler **light,
                     struct err *e)
{
    uint64_t pool_seed = rng_mix64(seed ^ 0x706f6f6cULL); /* "pool": the pools' own stream */
    *light = NULL;
    if (!(*pix = sampler_new(j->sampler, j->threshold, j->poisson_pool, pool_seed, e)) ||
        !(*light = sampler_new(j->light_sampler, j->light_threshold, j->poisson_pool, pool_seed + 1, e))) {
        sampler_free(*pix);
        *pix = NULL;
        return -1;
    }
    sampler_set_domain(*pix, j->poisson_domain);
    sampler_set_domain(*light, j->poisson_domain);
    return 0;
}
