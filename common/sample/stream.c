/* stream: a light's points taken one at a time from shuffled sets (stream.h). */
#include "stream.h"

#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/vec3.h"

int stream_source_init(struct stream_source *src, struct sampler *s, struct err *e)
{
    *src = (struct stream_source){0};
    src->sampler = s;
    src->walk = sampler_walk_of(s);
    src->grid = sampler_grid_of(s);
    /* a grid's cells (made when taken), a pool set's or a sobol set's points (by index); none for
       a set drawn whole (a fresh Poisson set's points are shuffled themselves) */
    src->cells = src->walk == SAMPLER_WALK_WHOLE ? 0 : sampler_set_capacity(s);
    if (src->cells == 0)
        return 0;
    src->identity = malloc(src->cells * sizeof *src->identity);
    if (!src->identity)
        return err_set(e, NULL, 0, 0, "out of memory for the light points' %zu indices", src->cells);
    for (size_t c = 0; c < src->cells; c++)
        src->identity[c] = (uint32_t)c;
    return 0;
}

void stream_source_release(struct stream_source *src)
{
    free(src->identity);
    src->identity = NULL;
}

int stream_init(struct stream *st, const struct stream_source *src)
{
    *st = (struct stream){0};
    if (src->cells > 0)
        st->cells = malloc(src->cells * sizeof *st->cells);
    else
        st->pts = malloc(sampler_set_capacity(src->sampler) * sizeof *st->pts);
    return st->cells || st->pts ? 0 : -1;
}

void stream_release(struct stream *st)
{
    free(st->pts);
    free(st->cells);
    st->pts = NULL;
    st->cells = NULL;
}

void stream_refill(const struct stream_source *src, struct stream *st, struct rng *rng)
{
    const enum sampler_walk walk = src->walk;
    const uint64_t t0 = src->timed_draw_ns ? clock_ns(CLOCK_MONOTONIC) : 0;
    if (st->cells) {
        st->n = walk == SAMPLER_WALK_POOL ? sampler_pool_set(src->sampler, rng, &st->pool, &st->ox, &st->oy)
                : walk == SAMPLER_WALK_SOBOL ? sampler_sobol_set(src->sampler, rng, &st->sobol)
                                             : sampler_cells(src->sampler);
        if (walk != SAMPLER_WALK_FREE) /* a set per pixel and light, a few dozen points used */
            memcpy(st->cells, src->identity, st->n * sizeof *st->cells);
        if (walk == SAMPLER_WALK_POOL)
            v3_sincos_turn(st->oy, &st->sin_oy, &st->cos_oy);
    } else {
        st->n = sampler_draw_at(src->sampler, rng, &st->at, st->pts);
        st->at.dim++; /* halton, zsobol: the pixel's next set of this light, a dimension of its own */
    }
    st->next = 0;
    if (src->timed_draw_ns)
        *src->timed_draw_ns += clock_ns(CLOCK_MONOTONIC) - t0;
    if (src->sets)
        ++*src->sets;
}
