/* study_fan: one render of a compare job or suite at a time. */
#include "study_fan.h"

#include <fcntl.h>
#include <stdio.h>
#include <sys/file.h>
#include <unistd.h>

#include "compare.h"
#include "compare_ref.h"
#include "study/load/compare_load.h"
#include "study/load/compare_suite_load.h"
#include "job/outdir.h"

int study_fan_load(const struct jobfile *jf, struct study_fan *f, struct err *e)
{
    f->c = NULL;
    f->s = NULL;
    if (jf->kind == JOBFILE_SUITE)
        f->s = compare_suite_load_doc(&jf->doc, jf->path, e);
    else
        f->c = compare_load_doc(&jf->doc, jf->path, e);
    return f->c || f->s ? 0 : -1;
}

void study_fan_free(struct study_fan *f)
{
    compare_suite_free(f->s);
    compare_free(f->c);
    f->s = NULL;
    f->c = NULL;
}

const char *study_fan_name(const struct study_fan *f)
{
    return f->s ? f->s->name : f->c->name;
}

int study_fan_studies(const struct study_fan *f)
{
    return f->s ? f->s->n_studies : 1;
}

struct compare *study_fan_study(const struct study_fan *f, int k)
{
    return f->s ? f->s->studies[k] : f->c;
}

int study_fan_has_reference(const struct study_fan *f, int k, int s)
{
    return study_fan_study(f, k)->scenes[s].ref_kind == COMPARE_REF_SETTINGS;
}

/* o for study k of f: a suite's study renders under OUT/<suite> (dir, n bytes). */
static struct run_opts study_opts(const struct study_fan *f, const struct run_opts *o, char *dir, size_t n)
{
    struct run_opts in = *o;
    if (f->s) {
        outdir_dir(o->out_dir, f->s->name, dir, n);
        in.out_dir = dir;
    }
    return in;
}

int study_fan_render(struct study_fan *f, int k, enum study_fan_kind kind, int index,
                     const struct run_opts *o, struct err *e)
{
    if (k < 0 || k >= study_fan_studies(f)) {
        err_set(e, NULL, 0, 0, "%s: no study %d", study_fan_name(f), k);
        return 2;
    }
    struct compare *c = study_fan_study(f, k);
    int count = kind == STUDY_FAN_REFERENCE ? c->n_scenes : c->n_items;
    if (index < 0 || index >= count) {
        err_set(e, NULL, 0, 0, "%s: no %s %d in study %d", study_fan_name(f),
                kind == STUDY_FAN_REFERENCE ? "reference" : "image", index, k);
        return 2;
    }
    char dir[2048];
    struct run_opts in = study_opts(f, o, dir, sizeof dir); /* as compare_suite_run has it */
    int rc = kind == STUDY_FAN_REFERENCE ? compare_ref_prepare(c, index, &c->results, &in, e)
                                         : compare_run_item(c, &c->results, index, &in, e);
    if (rc == 1)
        err_prefix(e, c->name);
    return rc;
}

int study_fan_render_job(struct study_fan *f, const struct study_fan_which *w, const struct run_opts *o,
                         struct job *j, struct run_opts *jo, char *dir, size_t n, struct err *e)
{
    int k = w->k, index = w->index;
    enum study_fan_kind kind = w->kind;
    struct compare *c = k >= 0 && k < study_fan_studies(f) ? study_fan_study(f, k) : NULL;
    int count = !c ? 0 : kind == STUDY_FAN_REFERENCE ? c->n_scenes : c->n_items;
    if (index < 0 || index >= count ||
        (kind == STUDY_FAN_REFERENCE && !study_fan_has_reference(f, k, index))) {
        err_set(e, NULL, 0, 0, "%s: no such render in study %d", study_fan_name(f), k);
        return 2;
    }
    *jo = study_opts(f, o, dir, n);
    if (kind == STUDY_FAN_REFERENCE) {
        jo->scene = &c->scenes[index].input->src;
        return compare_ref_half_target(c, index, w->half, jo, j) ? 3 : 0;
    }
    jo->scene = &c->scenes[c->items[index].scene].input->src;
    int rc = compare_item_job(c, &c->results, index, jo, j, e);
    if (rc == 1)
        err_prefix(e, c->name);
    return rc;
}

int study_fan_render_half(struct study_fan *f, int k, int s, int h, const struct run_opts *o, struct err *e)
{
    char dir[2048];
    struct run_opts in = study_opts(f, o, dir, sizeof dir);
    if (k < 0 || k >= study_fan_studies(f) || s < 0 || s >= study_fan_study(f, k)->n_scenes ||
        !study_fan_has_reference(f, k, s)) {
        err_set(e, NULL, 0, 0, "%s: no reference %d in study %d", study_fan_name(f), s, k);
        return 2;
    }
    return compare_ref_half_render(study_fan_study(f, k), s, h, &in, e);
}

int study_fan_half_merged(struct study_fan *f, int k, int s, int h, const struct run_opts *o, struct err *e)
{
    char dir[2048];
    struct run_opts in = study_opts(f, o, dir, sizeof dir);
    return compare_ref_half_merged(study_fan_study(f, k), s, h, &in, e) < 0;
}

int study_fan_ref_lock(const struct study_fan *f, int k, int s, const struct run_opts *o, int shared,
                       struct err *e)
{
    char dir[2048], cache[2048], lock[2400];
    outdir_dir(study_opts(f, o, dir, sizeof dir).out_dir, ".cache", cache, sizeof cache);
    if (outdir_mkdirs(cache, NULL, e) < 0)
        return -1;
    snprintf(lock, sizeof lock, "%s/.ref-%s.lock", cache, study_fan_study(f, k)->scenes[s].name);
    int fd = open(lock, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd >= 0)
        (void)flock(fd, shared ? LOCK_SH : LOCK_EX); /* released by close, or by the holder's death */
    return fd;
}

/* Scene s of study k's reference rendered or reused under its lock, so that the tasks of one array
   render it once. 0, 1 or 2. */
static int reference_locked(struct study_fan *f, int k, int s, const struct run_opts *o, struct err *e)
{
    int fd = study_fan_ref_lock(f, k, s, o, 0, e);
    if (fd < 0 && e->msg[0])
        return 2;
    int rc = study_fan_render(f, k, STUDY_FAN_REFERENCE, s, o, e);
    if (fd >= 0)
        close(fd);
    return rc;
}

int study_fan_share(const struct jobfile *jf, const struct run_opts *o)
{
    const char *path = jf->path;
    struct study_fan f;
    struct err e = {0};
    char line[4096];
    int rc = study_fan_load(jf, &f, &e) < 0 ? 2 : 0, rendered = 0, current = 0, index = 0;
    struct run_opts whole = *o; /* each image renders whole: the share is of the study, not of rows */
    whole.part = whole.parts = 0;
    for (int k = 0; rc == 0 && k < study_fan_studies(&f); k++) { /* none when the load failed */
        struct compare *c = study_fan_study(&f, k);
        int ready[COMPARE_MAX_ITEMS] = {0}; /* per scene: its reference prepared */
        for (int i = 0; i < c->n_items && rc == 0; i++, index++) {
            int s = c->items[i].scene;
            if (index % o->parts != o->part)
                continue;
            if (!ready[s] && study_fan_has_reference(&f, k, s))
                rc = reference_locked(&f, k, s, &whole, &e);
            ready[s] = 1;
            if (rc == 0)
                rc = study_fan_render(&f, k, STUDY_FAN_IMAGE, i, &whole, &e);
            rendered += rc == 0 && !c->results.rows[i].skipped;
            current += rc == 0 && c->results.rows[i].skipped;
        }
    }
    if (rc != 0) {
        err_format(&e, line, sizeof line);
        err_print("%s\n", line);
    } else
        err_print(
            "%s: part %d/%d: %d image%s rendered, %d current (not rendered again) -> %s/%s/; gather with "
            "worker %s --out %s\n",
            study_fan_name(&f), o->part, o->parts, rendered, rendered == 1 ? "" : "s", current,
            outdir_root(o->out_dir), study_fan_name(&f), path, outdir_root(o->out_dir));
    study_fan_free(&f);
    return rc;
}
