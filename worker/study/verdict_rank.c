/* verdict_rank: rank variants best first, tied where their seeds' spread covers the gap. */
#include "verdict_rank.h"

#include <math.h>

int verdict_beats(const struct verdict_entry *a, const struct verdict_entry *b, int log_scale)
{
    if (a->unreached != b->unreached)
        return b->unreached;
    if (!log_scale)
        return a->value < b->value && b->value - a->value > fmax(a->hi - a->lo, b->hi - b->lo);
    if (!(a->value > 0 && b->value > 0 && a->lo > 0 && b->lo > 0))
        return 0;
    return a->value < b->value && log(b->value / a->value) > fmax(log(a->hi / a->lo), log(b->hi / b->lo));
}

void verdict_rank(struct verdict_ranking *r, int n_seeds)
{
    for (int i = 1; i < r->n; i++) /* insertion sort, lowest value first: a handful of variants */
        for (int j = i;
             j > 0 && (r->e[j].unreached < r->e[j - 1].unreached ||
                       (r->e[j].unreached == r->e[j - 1].unreached && r->e[j].value < r->e[j - 1].value));
             j--) {
            struct verdict_entry t = r->e[j];
            r->e[j] = r->e[j - 1];
            r->e[j - 1] = t;
        }
    int first = 0;
    for (int i = 0; i < r->n; i++) {
        r->e[i].rank = 1;
        for (int j = 0; j < r->n; j++)
            r->e[i].rank += n_seeds > 1 && verdict_beats(&r->e[j], &r->e[i], r->log_scale);
        first += r->e[i].rank == 1;
    }
    /* The tie rule is not transitive: a variant with a wide spread may be beaten by none though
       its mean is worse than one that is beaten (ranks 1, 2, 1 by value). Best first is by rank,
       then value: a stable insertion sort keeps the value order within a rank. */
    for (int i = 1; i < r->n; i++)
        for (int j = i; j > 0 && r->e[j].rank < r->e[j - 1].rank; j--) {
            struct verdict_entry t = r->e[j];
            r->e[j] = r->e[j - 1];
            r->e[j - 1] = t;
        }
    r->status = n_seeds < 2 || first == r->n ? VERDICT_INCONCLUSIVE
                : first == 1                 ? VERDICT_CLEAR
                                             : VERDICT_TIE;
}
