/* rejudge: `worker verdict DIR [--json]`: read a compare output folder back and print its verdict. */
#include "rejudge.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/sbuf.h"
#include "study/run/verdict_load.h"
#include "study/load/study_env.h"
#include "study/present/verdict_out.h"

/* One line "a: b: c" (b may be NULL) as the terminal sanitiser shows it: the names in it come from
   summary.csv, which anyone may have written. */
static void say(const char *a, const char *b, const char *c)
{
    struct sbuf line = {0};
    sbuf_shown(&line, a);
    sbuf_printf(&line, ": ");
    if (b) {
        sbuf_shown(&line, b);
        sbuf_printf(&line, ": ");
    }
    sbuf_shown(&line, c);
    if (line.buf)
        printf("%s\n", line.buf);
    sbuf_free(&line);
}

/* Per study and scene: its sentences and failures, one line each. */
static void print_text(const char *job, const struct verdict_study *s, int n)
{
    char text[VERDICT_TEXT_MAX + 16];
    for (int i = 0; i < n; i++)
        for (int k = 0; k < s[i].n_scenes; k++) {
            const struct verdict_scene *v = &s[i].scenes[k];
            for (int l = 0; l < v->n_sentences; l++)
                say(s[i].name, v->scene, v->sentences[l]);
            for (int l = 0; l < v->n_failures; l++) {
                snprintf(text, sizeof text, "failure: %s", v->failures[l].text);
                say(s[i].name, v->scene, text);
            }
        }
    char winners[2048], all[2100];
    verdict_summary(s, n, winners, sizeof winners);
    snprintf(all, sizeof all, "at equal CPU time: %s", winners);
    say(job, NULL, all);
}

int rejudge_main(int argc, char **argv)
{
    const char *dir = NULL;
    int json = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--json"))
            json = 1;
        else if (!strcmp(argv[i], "--quiet") || !strcmp(argv[i], "-q"))
            continue; /* the common option: verdict prints no progress to quiet */
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: worker verdict DIR [--json] [--quiet]\n"
                   "the verdict of the compare job or suite whose output folder is DIR, judged again from\n"
                   "its summary.csv (images, sidecars and reference where present; the checks that need\n"
                   "what is missing are named as skipped); --json prints verdict.json's text\n");
            return 0;
        } else if (argv[i][0] == '-' || dir) {
            fprintf(stderr,
                    "worker verdict: unexpected argument %s; usage: worker verdict DIR [--json] [--quiet]\n",
                    argv[i]);
            return 2;
        } else
            dir = argv[i];
    }
    if (!dir) {
        fprintf(stderr, "worker verdict: no folder given; usage: worker verdict DIR [--json] [--quiet]\n");
        return 2;
    }
    struct verdict_study *s = NULL;
    struct err e = {0};
    char job[256], buf[2048];
    int n = 0, rc = 0;
    if (verdict_load_dir(dir, &s, &n, job, sizeof job, &e) < 0) {
        err_format(&e, buf, sizeof buf);
        fprintf(stderr, "worker verdict: %s\n", buf);
        rc = 2;
    } else if (json) {
        struct study_env env;
        study_env_read(&env); /* of this judging, not of the renders */
        char *text = verdict_json_text(job, s, n, &env);
        if (text)
            fputs(text, stdout);
        else
            rc = 2;
        free(text);
    } else {
        verdict_print_warnings(s, n);
        print_text(job, s, n);
    }
    for (int i = 0; i < n; i++)
        verdict_study_free(&s[i]);
    free(s);
    return rc;
}
