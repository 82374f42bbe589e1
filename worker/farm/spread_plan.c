/* spread_plan: a study's renders estimated by the cost model, cut into entries of about a target's
   CPU seconds, ordered by the critical path, and their predicted wall time on a farm. */
#include "spread_plan.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fileio.h"
#include "base/sbuf.h"
#include "job/job_estimate.h"
#include "job/part.h"
#include "study/run/compare_ref.h"
#include "study/run/study_scenes.h"

/* Append one render of est (its CPU and rows) as entries of at most about target_s each. */
static int add_render(struct spread_plan *p, const struct spread_entry *proto, const struct job_estimate *est,
                      double target_s, struct err *e)
{
    int parts = est->cpu_s > target_s ? (int)ceil(est->cpu_s / target_s) : 1;
    if (parts > PART_MAX)
        parts = PART_MAX;
    if (parts > est->height)
        parts = est->height;
    if (parts < 1)
        parts = 1;
    for (int i = 0; i < parts; i++) {
        if (p->n == p->cap) {
            int ncap = p->cap ? 2 * p->cap : 64;
            struct spread_entry *ne = realloc(p->e, (size_t)ncap * sizeof *ne);
            if (!ne)
                return err_set(e, NULL, 0, 0, "out of memory");
            p->e = ne, p->cap = ncap;
        }
        struct spread_entry *x = &p->e[p->n++];
        *x = *proto;
        x->part = i;
        x->parts = parts;
        x->processes = est->processes;
        x->est_cpu_s = est->cpu_s / parts; /* rows interleaved (row % N): the parts cost alike */
        char cut[32] = "";
        if (parts > 1)
            snprintf(cut, sizeof cut, "-p%d-%d", i, parts);
        if (x->kind == STUDY_FAN_REFERENCE)
            snprintf(x->name, sizeof x->name, "a-ref-%d-%d-%d%s.yaml", x->k, x->index, x->half, cut);
        else
            snprintf(x->name, sizeof x->name, "b-img-%d-%05d%s.yaml", x->k, x->index, cut);
        p->total_cpu_s += x->est_cpu_s;
    }
    return 0;
}

/* Claim order: references first (every image waits for them), then the longest; ties by study,
   render, half and part. */
static int by_critical_path(const void *pa, const void *pb)
{
    const struct spread_entry *a = pa, *b = pb;
    if (a->kind != b->kind)
        return a->kind == STUDY_FAN_REFERENCE ? -1 : 1;
    if (a->est_cpu_s != b->est_cpu_s)
        return a->est_cpu_s > b->est_cpu_s ? -1 : 1;
    int d = a->k != b->k           ? a->k - b->k
            : a->index != b->index ? a->index - b->index
            : a->half != b->half   ? a->half - b->half
                                   : a->part - b->part;
    return (d > 0) - (d < 0);
}

/* Study k's renders estimated (each seedless combination once) and appended. 0 or -1 with e. */
static int plan_study(const struct study_fan *f, int k, const struct study_scenes *ps, struct cost_model *m,
                      double target_s, int processes, struct spread_plan *p, struct err *e)
{
    const struct compare *c = study_fan_study(f, k);
    struct job_estimate est;
    for (int s = 0; s < c->n_scenes; s++) {
        if (!study_fan_has_reference(f, k, s))
            continue;
        for (int h = 0; h < 2; h++) {
            struct job hj;
            compare_ref_half_job(&c->scenes[s], h, &hj);
            double t = hj.entry_cpu_s > 0 ? hj.entry_cpu_s : target_s;
            struct spread_entry proto = {.kind = STUDY_FAN_REFERENCE, .k = k, .index = s, .half = h};
            if (job_estimate(&hj, study_scenes_of(ps, &c->scenes[s]), processes, m, &est, e) < 0 ||
                add_render(p, &proto, &est, t, e) < 0)
                return -1;
        }
    }
    for (int i = 0; i < c->n_items; i++) {
        const struct compare_item *it = &c->items[i];
        /* seeds cost alike: est holds the combination's first seed's (seeds are the innermost index) */
        if (it->seed == 0 &&
            job_estimate(&it->job, study_scenes_of(ps, &c->scenes[it->scene]), processes, m, &est, e) < 0)
            return -1;
        double t = it->job.entry_cpu_s > 0 ? it->job.entry_cpu_s : target_s;
        struct spread_entry proto = {.kind = STUDY_FAN_IMAGE, .k = k, .index = i};
        if (add_render(p, &proto, &est, t, e) < 0)
            return -1;
    }
    return 0;
}

int spread_plan_make(const struct study_fan *f, double target_s, int processes, struct spread_plan *p,
                     struct err *e)
{
    struct study_scenes ps = {0};
    struct cost_model *m = cost_model_new(SPREAD_PLAN_BUDGET_S);
    const int n = study_fan_studies(f);
    struct compare **studies = calloc((size_t)(n > 0 ? n : 1), sizeof *studies);
    int rc = -1;
    memset(p, 0, sizeof *p);
    for (int k = 0; studies && k < n; k++)
        studies[k] = study_fan_study(f, k);
    if (!m || !studies)
        err_set(e, NULL, 0, 0, "out of memory");
    else if (study_scenes_prepare(studies, n, &ps, m, e) == 0) {
        rc = 0;
        for (int k = 0; k < study_fan_studies(f) && rc == 0; k++)
            rc = plan_study(f, k, &ps, m, target_s, processes, p, e);
    }
    if (rc == 0 && p->n > 0)
        qsort(p->e, (size_t)p->n, sizeof *p->e, by_critical_path);
    study_scenes_free(&ps);
    free(studies);
    cost_model_free(m);
    if (rc < 0)
        spread_plan_free(p);
    return rc;
}

void spread_plan_free(struct spread_plan *p)
{
    free(p->e);
    memset(p, 0, sizeof *p);
}

int spread_plan_parse(const char *name, struct spread_entry *out)
{
    int a, b, c, part = 0, parts = 1, used = 0;
    char tail[16];
    memset(out, 0, sizeof *out);
    if (sscanf(name, "a-ref-%d-%d-%d%n", &a, &b, &c, &used) == 3) {
        out->kind = STUDY_FAN_REFERENCE;
        out->half = c;
        if (c != 0 && c != 1)
            return -1;
    } else if (sscanf(name, "b-img-%d-%d%n", &a, &b, &used) == 2) {
        out->kind = STUDY_FAN_IMAGE;
    } else {
        return -1;
    }
    out->k = a;
    out->index = b;
    const char *rest = name + used;
    int more = 0;
    if (sscanf(rest, "-p%d-%d%n", &part, &parts, &more) == 2)
        rest += more;
    if (snprintf(tail, sizeof tail, "%s", rest) >= (int)sizeof tail || strcmp(tail, ".yaml") || a < 0 ||
        b < 0 || parts < 1 || parts > PART_MAX || part < 0 || part >= parts)
        return -1;
    out->part = part;
    out->parts = parts;
    snprintf(out->name, sizeof out->name, "%s", name);
    return 0;
}

char *spread_plan_text(const struct spread_plan *p)
{
    struct sbuf b = {0};
    for (int i = 0; i < p->n; i++)
        sbuf_printf(&b, "%.6g %d %c %s\n", p->e[i].est_cpu_s, p->e[i].processes,
                    p->e[i].kind == STUDY_FAN_REFERENCE ? 'a' : 'b', p->e[i].name);
    return b.buf ? sbuf_take(&b) : calloc(1, 1);
}

int spread_plan_read(const char *path, struct spread_plan *p)
{
    uint8_t *data = NULL;
    size_t len = 0;
    struct err ignored;
    int cap = 0;
    memset(p, 0, sizeof *p);
    if (fileio_read_all(path, 1 << 24, &data, &len, &ignored) < 0)
        return -1;
    char *text = (char *)data, *save = NULL; /* NUL-terminated by fileio_read_all */
    for (char *line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
        struct spread_entry x = {0};
        char kind, name[64];
        if (sscanf(line, "%lf %d %c %63s", &x.est_cpu_s, &x.processes, &kind, name) != 4 ||
            !(x.est_cpu_s >= 0 && x.est_cpu_s < 1e12) || x.processes < 1 || (kind != 'a' && kind != 'b'))
            continue;
        if (p->n == cap) {
            int ncap = cap ? 2 * cap : 64;
            struct spread_entry *ne = realloc(p->e, (size_t)ncap * sizeof *ne);
            if (!ne)
                break;
            p->e = ne, cap = ncap;
        }
        x.kind = kind == 'a' ? STUDY_FAN_REFERENCE : STUDY_FAN_IMAGE;
        snprintf(x.name, sizeof x.name, "%s", name);
        p->e[p->n++] = x;
        p->total_cpu_s += x.est_cpu_s;
    }
    free(text);
    return 0;
}

double spread_plan_makespan(const struct spread_entry *e, int n, int workers, int cores)
{
    if (workers < 1 || cores < 1 || n < 1)
        return 0;
    double *free_at = calloc((size_t)workers, sizeof *free_at);
    if (!free_at)
        return NAN;
    double refs_end = 0, end = 0;
    for (int i = 0; i < n; i++) {
        int w = 0;
        for (int j = 1; j < workers; j++)
            if (free_at[j] < free_at[w])
                w = j;
        int use = e[i].processes < cores ? e[i].processes : cores;
        double start = free_at[w];
        /* an image waits until every reference has ended (they come first in claim order) */
        if (e[i].kind == STUDY_FAN_IMAGE && start < refs_end)
            start = refs_end;
        free_at[w] = start + e[i].est_cpu_s / (use > 0 ? use : 1);
        if (e[i].kind == STUDY_FAN_REFERENCE && free_at[w] > refs_end)
            refs_end = free_at[w];
        end = free_at[w] > end ? free_at[w] : end;
    }
    free(free_at);
    return end;
}
