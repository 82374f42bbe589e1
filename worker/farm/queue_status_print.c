/* queue_status_print: status's printers (queue_status_print.h). */
#include "queue_status_print.h"

#include <math.h>
#include <stdio.h>

#include "base/json.h"
#include "base/sbuf.h"
#include "queue_log.h"

/* Elapsed seconds of a running entry (since its claim) and its ETA (-1: unknown). */
static void running_times(const struct status_entry *x, double *elapsed, double *eta)
{
    *elapsed = x->age_s >= 0 && x->lease.start > 0 && time(NULL) >= x->lease.start
                   ? (double)(time(NULL) - x->lease.start)
                   : -1;
    *eta = -1;
    if (x->lease.rows > 0 && x->lease.rows_done > 0)
        *eta = x->lease.render_s * (x->lease.rows - x->lease.rows_done) / x->lease.rows_done;
}

static double percent(const struct status_entry *x)
{
    return x->lease.rows > 0 ? 100.0 * x->lease.rows_done / x->lease.rows : 0;
}

/* Room for a name of 256 bytes as the terminal sanitiser shows it (sbuf_show): 4 per byte. */
#define SHOWN_MAX 1025

void queue_status_print_text(const char *dir, const struct status_view *v)
{
    char when[64], name[SHOWN_MAX], reason[4 * 512 + 1]; /* names and reasons shown, never raw */
    const struct queue_waiting *w = v->w;
    const struct status_entry *r = v->r, *dn = v->dn, *f = v->f;
    int nw = v->nw, nr = v->nr, nd = v->nd, nf = v->nf;
    char shown_dir[4 * 1024 + 1];
    printf("queue %s: %d waiting, %d running, %d done, %d failed",
           sbuf_show(dir, shown_dir, sizeof shown_dir), nw, nr, nd, nf);
    if (v->ns)
        printf(", %d stud%s spread over it", v->ns, v->ns == 1 ? "y" : "ies");
    printf("\n");
    if (nw)
        printf("waiting (in claim order):\n");
    for (int i = 0; i < nw; i++) {
        printf("  %3d. %s  priority %d  queued %s\n", i + 1, sbuf_show(w[i].name, name, sizeof name),
               w[i].priority, queue_log_time(w[i].mtime.tv_sec, when, sizeof when));
    }
    if (nr)
        printf("running:\n");
    for (int i = 0; i < nr; i++) {
        double elapsed, eta;
        running_times(&r[i], &elapsed, &eta);
        if (r[i].age_s < 0) {
            printf("  %s  (no lease yet)\n", sbuf_show(r[i].file, name, sizeof name));
            continue;
        }
        char eta_s[32] = "--", elapsed_s[32] = "--";
        if (eta >= 0)
            snprintf(eta_s, sizeof eta_s, "%.0f s", eta);
        if (elapsed >= 0)
            snprintf(elapsed_s, sizeof elapsed_s, "%.0f s", elapsed);
        printf("  %s  host %s  pid %ld  attempt %d  %.0f%% (%d/%d rows)  elapsed %s  ETA %s%s\n",
               sbuf_show(r[i].file, name, sizeof name), r[i].lease.host, r[i].lease.pid, r[i].lease.attempt,
               percent(&r[i]), r[i].lease.rows_done, r[i].lease.rows, elapsed_s, r[i].gone ? "--" : eta_s,
               r[i].gone ? "  (its worker is gone: the next worker to scan takes it back)" : "");
    }
    queue_studies_print(v->studies, v->ns);
    if (nd)
        printf("done:\n");
    for (int i = 0; i < nd; i++) {
        queue_log_time(dn[i].when.tv_sec, when, sizeof when);
        const char *file = sbuf_show(dn[i].file, name, sizeof name);
        if (dn[i].wall_s < 0)
            printf("  %s  finished %s  (no sidecar)\n", file, when);
        else if (dn[i].images > 1) /* a compare job: its images' figures summed */
            printf("  %s  finished %s  %d images  wall (sum) %.2f s  cpu %.2f s  samples %.0f\n", file, when,
                   dn[i].images, dn[i].wall_s, dn[i].cpu_s, dn[i].samples);
        else
            printf("  %s  finished %s  wall %.2f s  cpu %.2f s  samples %.0f\n", file, when, dn[i].wall_s,
                   dn[i].cpu_s, dn[i].samples);
    }
    if (nf)
        printf("failed:\n");
    for (int i = 0; i < nf; i++)
        printf("  %s  %s\n", sbuf_show(f[i].file, name, sizeof name),
               sbuf_show(f[i].reason, reason, sizeof reason));
}

static void json_maybe(struct json *js, const char *key, double v)
{
    json_number(js, key, v < 0 ? (double)NAN : v); /* non-finite: null (unknown) */
}

void queue_status_print_json(const char *dir, const struct status_view *v)
{
    struct json js;
    char when[64];
    const struct queue_waiting *w = v->w;
    const struct status_entry *r = v->r, *dn = v->dn, *f = v->f;
    int nw = v->nw, nr = v->nr, nd = v->nd, nf = v->nf;
    json_init(&js);
    json_begin_object(&js, NULL);
    json_string(&js, "queue", dir);
    json_begin_array(&js, "waiting");
    for (int i = 0; i < nw; i++) {
        json_begin_object(&js, NULL);
        json_string(&js, "file", w[i].name);
        json_number(&js, "priority", w[i].priority);
        json_string(&js, "queued", queue_log_time(w[i].mtime.tv_sec, when, sizeof when));
        json_end_object(&js);
    }
    json_end_array(&js);
    json_begin_array(&js, "running");
    for (int i = 0; i < nr; i++) {
        double elapsed, eta;
        running_times(&r[i], &elapsed, &eta);
        json_begin_object(&js, NULL);
        json_string(&js, "file", r[i].file);
        json_string(&js, "name", r[i].name);
        json_string(&js, "host", r[i].lease.host);
        json_number(&js, "pid", (double)r[i].lease.pid);
        json_number(&js, "attempt", r[i].lease.attempt);
        json_number(&js, "processes", r[i].lease.processes);
        json_number(&js, "rows_done", r[i].lease.rows_done);
        json_number(&js, "rows", r[i].lease.rows);
        json_number(&js, "percent", percent(&r[i]));
        json_maybe(&js, "elapsed_s", elapsed);
        json_maybe(&js, "eta_s", eta);
        json_maybe(&js, "lease_age_s", r[i].age_s);
        json_bool(&js, "worker_gone", r[i].gone);
        json_end_object(&js);
    }
    json_end_array(&js);
    queue_studies_json(&js, v->studies, v->ns);
    json_begin_array(&js, "done");
    for (int i = 0; i < nd; i++) {
        json_begin_object(&js, NULL);
        json_string(&js, "file", dn[i].file);
        json_string(&js, "name", dn[i].name);
        json_string(&js, "finished", queue_log_time(dn[i].when.tv_sec, when, sizeof when));
        json_maybe(&js, "wall_s", dn[i].wall_s);
        json_maybe(&js, "cpu_s", dn[i].cpu_s);
        json_maybe(&js, "samples", dn[i].samples);
        json_number(&js, "images", dn[i].images);
        json_end_object(&js);
    }
    json_end_array(&js);
    json_begin_array(&js, "failed");
    for (int i = 0; i < nf; i++) {
        json_begin_object(&js, NULL);
        json_string(&js, "file", f[i].file);
        json_string(&js, "name", f[i].name);
        json_string(&js, "failed", queue_log_time(f[i].when.tv_sec, when, sizeof when));
        json_string(&js, "reason", f[i].reason);
        json_end_object(&js);
    }
    json_end_array(&js);
    json_end_object(&js);
    if (!js.oom)
        printf("%.*s\n", (int)js.len, js.buf);
    json_free(&js);
}
