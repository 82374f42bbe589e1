/* compare_suite_load: reading a suite (`name:` and `studies:`) and loading every study it lists,
   each checked as a compare job of its own, before anything renders. */
#include "compare_suite_load.h"
#include "compare_load.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/fileio.h"
#include "job/job.h"
#include "scenefile/yget.h"

/* The only keys of a suite's top level: every setting belongs to a study. */
static const char *const suite_keys[] = {"name", "studies", NULL};

/* A compare job's own keys (compare_load.c's), refused here with a note rather than as unknown. */
static const char *const study_only[] = {"scenes", "variants", "sweep", "seeds", NULL};

/* The suite's own outputs in OUT/<suite>/: no study may be named as one (its folder would take
   the file's place). */
static const char *const top_files[] = {"summary.csv", "chart.svg", "report.html", "verdict.json", NULL};

static int in_list(const char *key, const char *const *list)
{
    for (int i = 0; list[i]; i++)
        if (!strcmp(key, list[i]))
            return 1;
    return 0;
}

/* The top level: name and studies only. A job or compare job key gets a note (the settings live
   in the study files), anything else ymap_check's "did you mean". */
static int check_top(struct ydoc *d, yaml_node_t *root, struct job *base, struct err *e)
{
    yaml_node_t *k, *v;
    const char *job_keys[JOB_KEYS_MAX + 1];
    job_key_list(job_keys, JOB_KEYS_MAX + 1);
    for (int i = 0; ymap_pair(d, root, i, &k, &v); i++) {
        const char *key = yscalar(k);
        if (key && !in_list(key, suite_keys) && (in_list(key, job_keys) || in_list(key, study_only)))
            return ydoc_fail(d, k, e,
                             "%s: not allowed in a suite (a job with studies:): it holds only name and "
                             "studies; set %s in the study files",
                             key, key);
    }
    if (ymap_check(d, root, suite_keys, "suite", e) < 0)
        return -1;
    for (int i = 0; ymap_pair(d, root, i, &k, &v); i++)
        if (!strcmp(yscalar(k), "name") && job_apply(base, d, k, v, e) < 0)
            return -1;
    return 0;
}

/* rel resolved beside the suite's file at path (absolute paths as they are). */
static void resolve(const char *path, const char *rel, char *out, size_t n)
{
    const char *slash = strrchr(path, '/');
    if (rel[0] == '/' || !slash)
        snprintf(out, n, "%s", rel);
    else
        snprintf(out, n, "%.*s/%s", (int)(slash - path), path, rel);
}

/* A study (parsed into sd) that lists studies itself: suites do not nest. 0, or -1 with e inside
   the study file. */
static int check_not_nested(struct ydoc *sd, struct err *e)
{
    yaml_node_t *root = ydoc_root(sd), *k, *v;
    for (int i = 0; root && root->type == YAML_MAPPING_NODE && ymap_pair(sd, root, i, &k, &v); i++)
        if (yscalar(k) && !strcmp(yscalar(k), "studies"))
            return ydoc_fail(sd, k, e,
                             "studies: a study cannot list studies itself (suites do not nest): list "
                             "them in the suite instead");
    return 0;
}

/* Study i, listed at node item: loaded, checked against the ones before it, owned by s. */
static int load_study(struct compare_suite *s, struct ydoc *d, yaml_node_t *item, int i, struct err *e)
{
    const char *rel;
    char study[JOB_PATH_MAX];
    struct stat st;
    if (ynull(item))
        return ydoc_fail(d, item, e,
                         "studies: an empty entry (null); give a study file, e.g. studies: [cost.yaml]");
    if (yget_string(d, item, "studies", &rel, e) < 0)
        return -1;
    resolve(s->path, rel, study, sizeof study);
    if (stat(study, &st) < 0)
        return ydoc_fail(d, item, e, "studies: no study file at %s (%s)", study, strerror(errno));
    if (!S_ISREG(st.st_mode))
        return ydoc_fail(d, item, e, "studies: %s is %s, not a study file", study, fileio_kind(study));
    struct ydoc sd; /* the study file read once: checked, then loaded */
    struct compare *c = ydoc_load(&sd, study, e) < 0 || check_not_nested(&sd, e) < 0
                            ? NULL
                            : compare_load_in(&sd, study, s->inputs, e);
    ydoc_free(&sd);
    if (!c)
        return -1;
    s->studies[s->n_studies++] = c;
    /* The suite's file rendered them: a sidecar's job_file names it, as a queue's check of who
       owns an output folder (queue_claim_name_owner) expects of the claimed file's outputs. */
    for (int k = 0; k < c->n_items; k++)
        snprintf(c->items[k].job.path, sizeof c->items[k].job.path, "%s", s->path);
    for (int k = 0; k < i; k++)
        if (!strcmp(s->studies[k]->path, c->path))
            return ydoc_fail(d, item, e, "studies: %s is listed twice", c->path);
        else if (!strcmp(s->studies[k]->name, c->name))
            return ydoc_fail(d, item, e,
                             "studies: %s and %s are both named \"%s\": their outputs would share OUT/%s/%s/ "
                             "(give one another name: in its file)",
                             s->studies[k]->path, c->path, c->name, s->name, c->name);
    if (in_list(c->name, top_files))
        return ydoc_fail(d, item, e,
                         "studies: %s is named \"%s\", as the suite's own %s/%s (rename the study)", c->path,
                         c->name, s->name, c->name);
    s->n_items += c->n_items;
    if (s->n_items > COMPARE_SUITE_MAX_ITEMS)
        return ydoc_fail(d, item, e,
                         "studies: the studies so far expand to %d images (a suite's limit is %d)",
                         s->n_items, COMPARE_SUITE_MAX_ITEMS);
    return 0;
}

struct compare_suite *compare_suite_load(const char *path, struct err *e)
{
    struct ydoc d;
    struct compare_suite *s = ydoc_load(&d, path, e) < 0 ? NULL : compare_suite_load_doc(&d, path, e);
    ydoc_free(&d);
    return s;
}

struct compare_suite *compare_suite_load_doc(const struct ydoc *doc, const char *path, struct err *e)
{
    struct compare_suite *s = calloc(1, sizeof *s);
    struct ydoc d = *doc; /* borrowed: read, freed by its owner */
    struct job base;
    int ok = 0;
    if (!s || !(s->inputs = study_inputs_new())) {
        free(s);
        err_set(e, path, 0, 0, "out of memory");
        return NULL;
    }
    snprintf(s->path, sizeof s->path, "%s", path);
    job_defaults(&base, path);
    yaml_node_t *root = ydoc_root(&d), *list;
    if (check_top(&d, root, &base, e) < 0 || job_check_stem(&base, e) < 0)
        goto done;
    snprintf(s->name, sizeof s->name, "%s", base.name);
    if (!(list = ymap_get(&d, root, "studies"))) {
        ymap_missing(&d, root, "studies", e, "studies: missing");
        goto done;
    }
    int n = yseq_len(list);
    if (n < 1) {
        ydoc_fail(&d, list, e,
                  "studies: must be a non-empty list of study files, e.g. studies: [a.yaml, b.yaml]");
        goto done;
    }
    if (n > COMPARE_SUITE_MAX_STUDIES) {
        ydoc_fail(&d, list, e, "studies: %d listed, at most %d", n, COMPARE_SUITE_MAX_STUDIES);
        goto done;
    }
    for (int i = 0; i < n; i++)
        if (load_study(s, &d, yseq_item(&d, list, i), i, e) < 0)
            goto done;
    ok = 1;
done:
    if (!ok) {
        compare_suite_free(s);
        return NULL;
    }
    return s;
}
