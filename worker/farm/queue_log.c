/* queue_log: timestamped, job-named queue log lines, and the host's render-process count. */
#include "queue_log.h"

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "base/err.h"
#include "queue_scan.h"

char *queue_log_time(time_t t, char *out, size_t n)
{
    struct tm tm;
    strftime(out, n, "%Y-%m-%dT%H:%M:%SZ", gmtime_r(&t, &tm));
    return out;
}

void queue_log(const char *file, const char *fmt, ...)
{
    char msg[4096], when[32];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    size_t n = strlen(msg);
    if (n > 0 && msg[n - 1] == '\n')
        msg[n - 1] = 0;
    err_print("%s %s: %s", queue_log_time(time(NULL), when, sizeof when), file, msg);
}

/* Render processes that the live claims in running/ held by workers on this host (its name and
   pid space, as `me` says) run now, by their leases, leaving out the claim at `skip`. */
static int host_processes(const char *running, const struct lease *me, const char *skip)
{
    DIR *d = opendir(running);
    int total = 0;
    if (!d)
        return 0;
    struct dirent *de;
    while ((de = readdir(d))) {
        char claim[2048];
        struct lease l;
        double age;
        if (!queue_scan_is_job_file(de->d_name))
            continue;
        snprintf(claim, sizeof claim, "%s/%s", running, de->d_name);
        if (!strcmp(claim, skip) || lease_read(claim, &l, &age) < 0)
            continue;
        int same_space =
            !strcmp(l.host, me->host) && (!l.pids[0] || !me->pids[0] || !strcmp(l.pids, me->pids));
        /* a holder that is gone renders nothing, whatever its lease says */
        if (same_space && l.pid > 0 && !(kill((pid_t)l.pid, 0) < 0 && errno == ESRCH))
            total += l.processes;
    }
    closedir(d);
    return total;
}

void queue_log_check_cores(const char *running, const struct lease *me, const char *claim, const char *file,
                           int processes)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    if (cores < 1)
        return;
    int others = host_processes(running, me, claim);
    if (others + processes > cores)
        queue_log(file,
                  "warning: the workers on %s run %d render processes on %ld cores (this job %d, others %d): "
                  "renders that share cores slow each other down (fewer workers, or --processes)",
                  me->host, others + processes, cores, processes, others);
}
