/* test_lease: lease files round-trip, and the rules that declare a claim's holder dead. */
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "farm/lease.h"

/* Set path's mtime seconds_ago into the past. */
static void age(const char *path, int seconds_ago)
{
    struct timespec t[2];
    clock_gettime(CLOCK_REALTIME, &t[0]);
    t[0].tv_sec -= seconds_ago;
    t[1] = t[0];
    utimensat(AT_FDCWD, path, t, 0);
}

static void touch(const char *path)
{
    FILE *f = fopen(path, "w");
    if (f)
        fclose(f);
}

/* A pid that existed and is gone: a reaped child's. */
static long dead_pid(void)
{
    pid_t p = fork();
    if (p == 0)
        _exit(0);
    waitpid(p, NULL, 0);
    return (long)p;
}

int main(void)
{
    char dir[] = "/tmp/test_lease.XXXXXX", claim[256], side[300], why[512];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(claim, sizeof claim, "%s/job.yaml", dir);
    snprintf(side, sizeof side, "%s.lease", claim);
    struct err e;
    struct lease me, got;
    double age_s = -1;

    /* a claim that is not there is nobody's business */
    CHECK(lease_stale(claim, 60, why, sizeof why) == 0);

    /* round trip; a fresh own-host lease of a live process is alive */
    touch(claim);
    lease_init(&me);
    CHECK(me.pid == (long)getpid());
    CHECK(me.host[0] != 0);
    me.pid = (long)getppid();
    CHECK(lease_write(claim, &me, &e) == 0);
    CHECK(lease_read(claim, &got, &age_s) == 0);
    CHECK(strcmp(got.host, me.host) == 0 && got.pid == me.pid && got.start == me.start);
    CHECK(strcmp(got.token, me.token) == 0);
    CHECK(age_s >= 0 && age_s < 5);
    CHECK(lease_stale(claim, 60, why, sizeof why) == 0);

    /* tokens differ between two claims of the same process */
    struct lease again;
    lease_init(&again);
    CHECK(strcmp(again.token, me.token) != 0);

    /* same host, pid gone: dead at once, whatever the lease's age */
    me.pid = dead_pid();
    CHECK(lease_write(claim, &me, &e) == 0);
    CHECK(lease_stale(claim, 3600, why, sizeof why) == 1);
    CHECK(strstr(why, "is gone") != NULL);

    /* this host's name but another pid space (a container sharing the hostname, a cloned machine):
       its pid means nothing here, so it is judged by the lease's age, as another host's */
    struct lease mine;
    lease_init(&mine);
    if (mine.pids[0]) {
        snprintf(me.pids, sizeof me.pids, "another-boot:pid:[1]");
        CHECK(lease_write(claim, &me, &e) == 0);
        CHECK(lease_read(claim, &got, &age_s) == 0);
        CHECK(strcmp(got.pids, me.pids) == 0);
        CHECK(lease_stale(claim, 60, why, sizeof why) == 0);
        age(side, 120);
        CHECK(lease_stale(claim, 60, why, sizeof why) == 1);
        CHECK(strstr(why, "has not renewed") != NULL);
        snprintf(me.pids, sizeof me.pids, "%s", mine.pids); /* our own pid space: gone at once */
        CHECK(lease_write(claim, &me, &e) == 0);
        CHECK(lease_stale(claim, 3600, why, sizeof why) == 1);
        me.pids[0] = 0; /* a lease of an earlier version (no pids line) is taken as this host's */
        CHECK(lease_write(claim, &me, &e) == 0);
        CHECK(lease_stale(claim, 3600, why, sizeof why) == 1);
    } else {
        printf("test_lease: no pid space known here (not Linux?), pid-space checks skipped\n");
    }

    /* a pid that names no single process (0, -1) is nobody's */
    me.pid = -1;
    CHECK(lease_write(claim, &me, &e) == 0);
    CHECK(lease_stale(claim, 3600, why, sizeof why) == 1);

    /* another host: alive while the lease is fresh, dead once older than the timeout */
    snprintf(me.host, sizeof me.host, "elsewhere.example");
    me.pid = 1;
    CHECK(lease_write(claim, &me, &e) == 0);
    CHECK(lease_stale(claim, 60, why, sizeof why) == 0);
    age(side, 120);
    CHECK(lease_stale(claim, 60, why, sizeof why) == 1);
    CHECK(strstr(why, "elsewhere.example") != NULL && strstr(why, "has not renewed") != NULL);
    lease_touch(claim); /* the holder renews: alive again */
    CHECK(lease_stale(claim, 60, why, sizeof why) == 0);

    /* no lease: judged by the claim's age (rename() sets its ctime); a fresh claim is alive */
    lease_remove(claim);
    CHECK(access(side, F_OK) != 0);
    CHECK(lease_read(claim, &got, &age_s) == -1);
    CHECK(lease_stale(claim, 60, why, sizeof why) == 0);
    CHECK(lease_stale(claim, -1, why, sizeof why) == 1);
    CHECK(strstr(why, "no lease") != NULL);

    /* a damaged lease reads as missing */
    FILE *f = fopen(side, "w");
    CHECK(f != NULL);
    if (f) {
        fputs("host x\n", f);
        fclose(f);
    }
    CHECK(lease_read(claim, &got, &age_s) == -1);

    /* the recovery lock: one holder at a time; a lock older than the timeout is broken */
    CHECK(lease_lock(claim, 60) == 0);
    CHECK(lease_lock(claim, 60) == -1);
    lease_unlock(claim);
    CHECK(lease_lock(claim, 60) == 0);
    char lock[300];
    snprintf(lock, sizeof lock, "%s.lock", claim);
    age(lock, 120);
    CHECK(lease_lock(claim, 60) == 0); /* breaks it and takes it */
    lease_unlock(claim);

    /* a lock whose holder (of this host) is gone, made since the claim was, on a claim without a
       lease: its filer was killed between removing the lease and the move. The claim is dead at
       once, and the lock is broken and taken at once (issue 36, defect 10) */
    remove(side);
    struct lease gone;
    lease_init(&gone);
    gone.pid = dead_pid();
    f = fopen(lock, "w");
    CHECK(f != NULL);
    if (f) {
        fprintf(f, "host %s\npid %ld\nstart %lld\ntoken %s\npids %s\n", gone.host, gone.pid, gone.start,
                gone.token, gone.pids);
        fclose(f);
    }
    CHECK(lease_stale(claim, 60, why, sizeof why) == 1);
    CHECK(strstr(why, "killed while it filed") != NULL);
    CHECK(lease_lock(claim, 60) == 0);
    CHECK(lease_stale(claim, 60, why, sizeof why) == 1); /* judged again under the lock taken from it */
    lease_unlock(claim);
    CHECK(lease_lock(claim, 60) == 0); /* a lock of our own, not taken from anyone: no verdict */
    CHECK(lease_stale(claim, 60, why, sizeof why) == 0);
    lease_unlock(claim);
    /* a dead holder's lock older than the claim is an earlier claim's: it says nothing of this one */
    f = fopen(lock, "w");
    if (f) {
        fprintf(f, "host %s\npid %ld\nstart %lld\ntoken %s\npids %s\n", gone.host, gone.pid, gone.start,
                gone.token, gone.pids);
        fclose(f);
    }
    age(lock, 30);
    CHECK(lease_stale(claim, 60, why, sizeof why) == 0);
    /* left behind once its claim is gone: swept (a live holder's, or one with its claim, stays) */
    char running[300], *slash;
    snprintf(running, sizeof running, "%s", claim);
    slash = strrchr(running, '/');
    if (slash)
        *slash = 0;
    lease_sweep_locks(running, strrchr(lock, '/') + 1, 60);
    CHECK(access(lock, F_OK) == 0);
    remove(claim);
    lease_sweep_locks(running, strrchr(lock, '/') + 1, 60);
    CHECK(access(lock, F_OK) != 0);

    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    return check_report("test_lease");
}
