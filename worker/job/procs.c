/* procs: fork N renderers over interleaved rows, share the framebuffer, reap and report. */
#include "procs.h"

#include <errno.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/resource.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "base/clock.h"

struct shared {
    atomic_int rows_done;
    struct procs_proc proc[PROCS_MAX_PROCESSES];
};

/* The child's whole life: render its rows into the mapping, write its stats, _exit. */
static void child_main(const struct procs_job *fj, int index, int nproc, float *rgb, struct shared *sh,
                       pid_t parent)
{
    /* With a stop flag the parent owns SIGINT/SIGTERM (a terminal's Ctrl-C or Slurm's scancel
       reach the whole process group): it stops the children itself, so a signal that reached a
       child first can never pass for a crash. Without one, they die as usual. */
    signal(SIGINT, fj->stop ? SIG_IGN : SIG_DFL);
    signal(SIGTERM, fj->stop ? SIG_IGN : SIG_DFL);
#ifdef __linux__
    /* Die with the worker at once: one row of a wide image at a low threshold takes minutes, and
       elsewhere a child only notices its parent's death between rows (getppid below). */
    prctl(PR_SET_PDEATHSIG, SIGKILL);
#endif
    if (getppid() != parent) /* the worker died before the line above */
        _exit(4);
    double wall0 = clock_s(CLOCK_MONOTONIC);
    struct err e;
    struct render_ctx *ctx = render_ctx_new(fj->scene, fj->camera, &fj->rs, fj->pixel, fj->light, &e);
    if (!ctx)
        _exit(3);
    struct render_stats st;
    render_stats_init(&st);
    const int w = fj->rs.width, h = fj->rs.height;
    int k = 0; /* index among this part's rows */
    for (int y = 0; y < h; y++) {
        if (y % fj->row_parts != fj->row_part)
            continue;
        if (k++ % nproc != index)
            continue;
        for (int x = 0; x < w; x++)
            render_pixel(ctx, x, y, &rgb[((size_t)y * w + x) * 3], &st);
        atomic_fetch_add(&sh->rows_done, 1);
        if (getppid() != parent) /* the worker was killed: nobody will read our rows */
            _exit(4);
    }
    render_ctx_free(ctx);
    const double cpu_s = clock_s(CLOCK_PROCESS_CPUTIME_ID);
    render_stats_finish(&st, cpu_s); /* sampler_s: a part of cpu_s, never more */
    sh->proc[index].st = st;
    sh->proc[index].wall_s = clock_s(CLOCK_MONOTONIC) - wall0;
    sh->proc[index].cpu_s = cpu_s;
    sh->proc[index].done = 1;
    _exit(0);
}

int procs_render_here(const struct procs_job *fj, float *rgb, struct procs_result *res, struct err *e)
{
    memset(res, 0, sizeof *res);
    res->processes = 1;
    const double wall0 = clock_s(CLOCK_MONOTONIC), cpu0 = clock_s(CLOCK_THREAD_CPUTIME_ID);
    struct render_ctx *ctx = render_ctx_new(fj->scene, fj->camera, &fj->rs, fj->pixel, fj->light, e);
    if (!ctx)
        return -1;
    struct render_stats st;
    render_stats_init(&st);
    const int w = fj->rs.width, h = fj->rs.height;
    for (int y = 0; y < h; y++)
        if (y % fj->row_parts == fj->row_part)
            for (int x = 0; x < w; x++)
                render_pixel(ctx, x, y, &rgb[((size_t)y * w + x) * 3], &st);
    render_ctx_free(ctx);
    res->cpu_s = clock_s(CLOCK_THREAD_CPUTIME_ID) - cpu0;
    render_stats_finish(&st, res->cpu_s);
    render_stats_init(&res->total);
    render_stats_add(&res->total, &st);
    res->wall_s = clock_s(CLOCK_MONOTONIC) - wall0;
    return 0;
}

static void kill_all(pid_t *pids, int n)
{
    for (int i = 0; i < n; i++)
        if (pids[i] > 0)
            kill(pids[i], SIGKILL);
    for (int i = 0; i < n; i++)
        if (pids[i] > 0)
            while (waitpid(pids[i], NULL, 0) < 0 && errno == EINTR)
                ;
}

float *procs_framebuffer_new(int w, int h, struct err *e)
{
    size_t bytes = (size_t)w * (size_t)h * 3 * sizeof(float);
    void *p = mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) {
        err_set(e, NULL, 0, 0, "cannot map a %dx%d framebuffer (%zu MB): %s", w, h, bytes >> 20,
                strerror(errno));
        return NULL;
    }
    return p;
}

void procs_framebuffer_free(float *rgb, int w, int h)
{
    if (rgb)
        munmap(rgb, (size_t)w * (size_t)h * 3 * sizeof(float));
}

double procs_sampling_share(const struct procs_result *r)
{
    return r->cpu_s > 0 ? r->total.sampler_s / r->cpu_s : 0;
}

int procs_render(const struct procs_job *fj, float *rgb, struct procs_result *res, struct err *e)
{
    const int h = fj->rs.height;
    int rows = 0;
    for (int y = 0; y < h; y++)
        rows += y % fj->row_parts == fj->row_part;
    int nproc = fj->processes < 1 ? 1 : fj->processes;
    if (nproc > PROCS_MAX_PROCESSES)
        nproc = PROCS_MAX_PROCESSES;
    if (nproc > rows && rows > 0)
        nproc = rows;
    memset(res, 0, sizeof *res);
    res->processes = nproc;
    struct shared *sh = mmap(NULL, sizeof *sh, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (sh == MAP_FAILED)
        return err_set(e, NULL, 0, 0, "cannot map shared memory: %s", strerror(errno));
    memset(sh, 0, sizeof *sh);
    atomic_init(&sh->rows_done, 0);
    pid_t pids[PROCS_MAX_PROCESSES] = {0};
    double wall0 = clock_s(CLOCK_MONOTONIC);
    pid_t parent = getpid();
    int rc = 0;
    for (int i = 0; i < nproc; i++) {
        pids[i] = fork();
        if (pids[i] < 0) {
            pids[i] = 0;
            kill_all(pids, i);
            munmap(sh, sizeof *sh);
            return err_set(e, NULL, 0, 0, "cannot start render process %d: %s", i + 1, strerror(errno));
        }
        if (pids[i] == 0)
            child_main(fj, i, nproc, rgb, sh, parent);
    }
    int left = nproc;
    long nap_ns = 100000;
    while (left > 0) {
        int status = 0;
        pid_t pid = waitpid(-1, &status, WNOHANG);
        if (pid < 0 && errno != EINTR)
            break;
        int i = 0;
        while (pid > 0 && i < nproc && pids[i] != pid)
            i++;
        if (i == nproc)
            continue; /* not ours */
        if (pid > 0) {
            pids[i] = 0;
            left--;
        }
        if (fj->stop && *fj->stop) {
            err_set(e, NULL, 0, 0, "render stopped by a signal");
            res->stopped = 1;
            rc = -1;
        } else if (pid <= 0) {
            if (fj->progress)
                fj->progress(fj->progress_arg, atomic_load(&sh->rows_done), rows,
                             clock_s(CLOCK_MONOTONIC) - wall0);
            /* naps from 0.1 ms doubling to 5 ms: a render of a millisecond (the cost design's
               repeated small images) is seen at once, a long one with about 200 cheap wake-ups a
               second (at 50 ms a 0.3 s job lost a sixth of its wall time to the wait) */
            struct timespec nap = {0, nap_ns};
            nanosleep(&nap, NULL);
            nap_ns = nap_ns < 5000000 / 2 ? 2 * nap_ns : 5000000;
            continue;
        } else if (WIFSIGNALED(status)) {
            res->child_signal = WTERMSIG(status);
            res->child_crashed = 1;
            err_set(e, NULL, 0, 0, "render process %d of %d (pid %d) was killed by signal %d (%s)", i + 1,
                    nproc, (int)pid, WTERMSIG(status), strsignal(WTERMSIG(status)));
            rc = -1;
        } else if (WEXITSTATUS(status) != 0 || !sh->proc[i].done) {
            res->child_crashed = 1;
            err_set(e, NULL, 0, 0, "render process %d of %d (pid %d) failed with exit code %d", i + 1, nproc,
                    (int)pid, WEXITSTATUS(status));
            rc = -1;
        }
        if (rc < 0) {
            kill_all(pids, nproc);
            break;
        }
    }
    if (rc == 0) {
        render_stats_init(&res->total);
        for (int i = 0; i < nproc; i++) {
            res->proc[i] = sh->proc[i];
            render_stats_add(&res->total, &sh->proc[i].st);
            res->cpu_s += sh->proc[i].cpu_s;
        }
        res->wall_s = clock_s(CLOCK_MONOTONIC) - wall0;
        struct rusage ru;
        if (getrusage(RUSAGE_CHILDREN, &ru) == 0)
            res->peak_rss_kb = ru.ru_maxrss;
        if (fj->progress)
            fj->progress(fj->progress_arg, rows, rows, res->wall_s);
    }
    munmap(sh, sizeof *sh);
    return rc;
}
