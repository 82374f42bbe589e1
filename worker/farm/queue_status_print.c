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

static void json_maybe(struct json *js, const char *key, double v)
{
    json_number(js, key, v < 0 ? (double)NAN : v); /* non-finite: null (unknown) */
}

/* The studies in progress: one line each under a "studies:" heading (nothing when n is 0). */
static void print_studies(const struct queue_studies_entry *s, int n)
{
    if (n)
        printf("studies (spread over the queue):\n");
    for (int i = 0; i < n; i++) {
        char eta[5000] = "--";
        char file[4 * sizeof s[i].file + 1], name[4 * sizeof s[i].name + 1]; /* shown, never raw */
        char damaged[4 * sizeof s[i].damaged + 1];
        sbuf_show(s[i].file, file, sizeof file);
        if (s[i].damaged[0])
            snprintf(eta, sizeof eta, "-- (its folder is damaged: %s)",
                     sbuf_show(s[i].damaged, damaged, sizeof damaged));
        else if (s[i].waits_requeue)
            snprintf(eta, sizeof eta,
                     "-- (waits for its failed renders to be requeued: worker requeue DIR %s)", file);
        else if (s[i].eta_s >= 0 || s[i].done == s[i].renders)
            snprintf(eta, sizeof eta, "%.0f s", s[i].eta_s >= 0 ? s[i].eta_s : 0);
        printf("  %s  study %s  %d/%d renders done, %d failed, %d running%s  elapsed %.0f s  ETA %s\n", file,
               sbuf_show(s[i].name, name, sizeof name), s[i].done, s[i].renders, s[i].failed, s[i].running,
               s[i].gathering ? ", gathering" : "", s[i].elapsed_s, eta);
        if (!s[i].planned)
            continue;
        char finish[160] = "no worker holds a lease now: no finish predicted";
        if (s[i].finish_s >= 0)
            snprintf(finish, sizeof finish,
                     "predicted finish in about %.0f s on the %d worker%s holding leases now", s[i].finish_s,
                     s[i].lease_workers, s[i].lease_workers == 1 ? "" : "s");
        printf("    CPU about %.0f s done, %.0f s left (estimated by the plan); %s\n", s[i].cpu_done_s,
               s[i].cpu_left_s, finish);
    }
}

/* The "studies" array of status --json. */
static void json_studies(struct json *js, const struct queue_studies_entry *s, int n)
{
    json_begin_array(js, "studies");
    for (int i = 0; i < n; i++) {
        json_begin_object(js, NULL);
        json_string(js, "file", s[i].file);
        json_string(js, "name", s[i].name);
        json_number(js, "renders", s[i].renders);
        json_number(js, "done", s[i].done);
        json_number(js, "failed", s[i].failed);
        json_number(js, "running", s[i].running);
        json_bool(js, "gathering", s[i].gathering);
        json_number(js, "elapsed_s", s[i].elapsed_s);
        json_maybe(js, "eta_s", s[i].eta_s);
        json_bool(js, "waits_for_requeue", s[i].waits_requeue);
        json_string(js, "damaged", s[i].damaged);
        if (s[i].planned) {
            json_number(js, "cpu_done_s", s[i].cpu_done_s);
            json_number(js, "cpu_left_s", s[i].cpu_left_s);
            json_number(js, "lease_workers", s[i].lease_workers);
            json_maybe(js, "finish_s", s[i].finish_s);
        }
        json_end_object(js);
    }
    json_end_array(js);
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
    print_studies(v->studies, v->ns);
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
    json_studies(&js, v->studies, v->ns);
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
    if (!js.text.oom)
        printf("%.*s\n", (int)js.text.len, js.text.buf);
    json_free(&js);
}
