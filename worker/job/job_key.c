/* job_key: the canonical text of everything that changes a render's pixels. */
#include "job_key.h"

#include <stdio.h>

/* What a key must add for the sets j's samplers make beyond the keys it prints: the Poisson
   domain when a sampler pools (poisson), the padding's version under sampler_dims: all ("" else),
   so that an image rendered by an earlier rule is never found current. */
static const char *sets_tag(const struct job *j, char *buf, size_t n)
{
    const int pooled =
        sampler_kind_has(j->sampler, SAMPLER_POOLED) || sampler_kind_has(j->light_sampler, SAMPLER_POOLED);
    const char *pad = j->dims_all ? " padded uniformly" : "";
    if (!pooled)
        snprintf(buf, n, "%s", pad);
    else /* the kind that pools has a domain: its name and the domain's (the hashes of old) */
        snprintf(buf, n, " %s %s%s", sampler_kind_name(SAMPLER_POISSON),
                 poisson_domain_name(j->poisson_domain), pad);
    return buf;
}

int job_key_text(const struct job *j, int width, int height, const char *middle, char *buf, size_t n)
{
    char tag[64];
    int len = snprintf(
        buf, n, "%dx%d %s %.17g %s %.17g depth %d seed %llu pool %d lights %d%s worker %s%s%s%s%s", width,
        height, sampler_kind_name(j->sampler), j->threshold, sampler_kind_name(j->light_sampler),
        j->light_threshold, j->max_depth, (unsigned long long)j->seed, j->poisson_pool, j->light_sampling,
        middle, WORKER_VERSION, integrator_traits(j->integrator)->hash_tag, j->dims_all ? " dims all" : "",
        sets_tag(j, tag, sizeof tag), job_roulette(j) ? " roulette" : "");
    return len < 0 ? 0 : (size_t)len >= n ? (int)n - 1 : len;
}
