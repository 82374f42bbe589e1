#!/bin/sh
# End to end: queue directories. Many workers render each job exactly once; a killed worker's
# claim is recovered; crashed renders are retried (or filed as failed with the signal); bad jobs
# go to failed/ and the worker carries on; signals hand the job back; priority and age order.
. tests/lib.sh
TS='[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z' # a queue log line's time (ISO 8601, UTC)
root=$(pwd)

tiny() { # tiny FILE [yaml lines...]: a 16x16 job that renders in a few milliseconds
    f=$1; shift
    { echo "scene: $root/scenes/checker.yaml"; echo "width: 16"; echo "height: 16"; echo "threshold: 50"
      echo "light_threshold: 50"; echo "processes: 1"; for l in "$@"; do echo "$l"; done; } >"$f"
}
slow() { # slow FILE: a job long enough (a third of a second here) to be interrupted mid-render
    { echo "scene: $root/scenes/checker.yaml"; echo "width: 64"; echo "height: 64"; echo "threshold: 3"
      echo "light_threshold: 50"; echo "processes: 1"; } >"$1"
}
gone() { # gone PID: the process ends (or is a zombie) within 5 s
    for _ in $(seq 1 250); do
        s=$(ps -o stat= -p "$1" 2>/dev/null)
        case "$s" in ''|Z*) return 0 ;; esac
        sleep 0.02
    done
    return 1
}
count() { # count GLOB: how many paths match
    n=0; for f in $1; do [ -e "$f" ] && n=$((n + 1)); done; echo "$n"
}

# a plain render of the slow job: every recovered or retried render must equal it byte for byte
mkdir -p "$T/ref"
slow "$T/ref/slow.yaml"
"$WORKER" --quiet --out "$T/plain" "$T/ref/slow.yaml" 2>/dev/null
check "plain render of the slow job" [ -s "$T/plain/slow/slow.png" ]

# 1. four workers started together on 40 tiny jobs: each rendered exactly once, none failed
Q=$T/q1; mkdir -p "$Q"
for i in $(seq 1 40); do tiny "$Q/j$i.yaml"; done
"$WORKER" --queue "$Q" --once --quiet 2>"$T/w1.log" & p1=$!
"$WORKER" --queue "$Q" --once --quiet 2>"$T/w2.log" & p2=$!
"$WORKER" --queue "$Q" --once --quiet 2>"$T/w3.log" & p3=$!
"$WORKER" --queue "$Q" --once --quiet 2>"$T/w4.log" & p4=$!
rcs=""; for p in $p1 $p2 $p3 $p4; do wait "$p"; rcs="$rcs$?"; done
check "4 workers: all exit 0 (got $rcs)" [ "$rcs" = 0000 ]
check "4 workers: 40 job files in done/" [ "$(count "$Q/done/*.yaml")" -eq 40 ]
check "4 workers: 40 images in done/" [ "$(count "$Q/done/j*/j*.png")" -eq 40 ]
check "4 workers: none in failed/" [ "$(count "$Q/failed/*")" -eq 0 ]
check "4 workers: none left waiting" [ "$(count "$Q/*.yaml")" -eq 0 ]
check "4 workers: running/ is empty" [ -z "$(ls -A "$Q/running")" ]
once=0
for i in $(seq 1 40); do
    n=$(cat "$T"/w[1-4].log | grep -cE "^$TS j$i\.yaml: j$i: 16x16")
    if [ "$n" -eq 1 ]; then once=$((once + 1)); else echo "j$i rendered $n times" >&2; fi
done
check "4 workers: each job rendered exactly once ($once of 40)" [ "$once" -eq 40 ]
workers=0
for w in 1 2 3 4; do grep -q "16x16" "$T/w$w.log" && workers=$((workers + 1)); done
echo "4 workers: $workers of 4 rendered at least one job"

# 1b. a scan reads a waiting file (for its priority) only when it changed since the last scan:
#     reading them all on every scan cost a queue of N jobs N*N/2 reads (465 for 30; on NFS,
#     round trips each). Counted with strace where it is installed.
if command -v strace >/dev/null; then
    Q=$T/q1b; mkdir -p "$Q"
    for i in $(seq 1 30); do tiny "$Q/j$i.yaml"; done
    # (LeakSanitizer cannot run under ptrace: a `make asan` build would fail on exit otherwise)
    ASAN_OPTIONS=detect_leaks=0 strace -f -e trace=openat -o "$T/q1b.trace" "$WORKER" --queue "$Q" --once --quiet \
        2>/dev/null; rc=$?
    opens=$(grep -c "\"$Q/j[0-9]*[.]yaml\"," "$T/q1b.trace")
    check "scan reads: exit 0 (got $rc)" [ "$rc" -eq 0 ]
    check "scan reads: 30 jobs done" [ "$(count "$Q/done/*.yaml")" -eq 30 ]
    check "scan reads: each waiting file read once or twice, not once per scan (got $opens)" [ "$opens" -le 60 ]
else
    echo "no strace: scan read count not checked"
fi

# 2. kill -9 a worker mid-job: a restarted worker recovers the stale claim and completes the job
Q=$T/q2; mkdir -p "$Q"; slow "$Q/slow.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/k1.log" & wpid=$!
child=$(render_child "$wpid")
check "kill worker: found its render process" [ -n "$child" ]
check "kill worker: the claim is in running/" [ -f "$Q/running/slow.yaml" ]
check "kill worker: the lease names the worker" grep -q "^pid $wpid\$" "$Q/running/slow.yaml.lease"
kill -9 "$wpid"; wait "$wpid" 2>/dev/null
check "kill worker: the claim stays in running/" [ -f "$Q/running/slow.yaml" ]
check "kill worker: no image in done/" [ ! -e "$Q/done/slow/slow.png" ]
check "kill worker: its render process stops" gone "$child"
# as if it had been killed while writing the image: its temporary file is left in done/slow/
mkdir -p "$Q/done/slow"; : >"$Q/done/slow/.slow.png.tmp.k9Xy2Z"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/k2.log"; rc=$?
check "kill worker: the next worker exits 0 (got $rc)" [ "$rc" -eq 0 ]
check "kill worker: it says why it took the claim back" grep -q "slow.yaml: returned to the queue: its worker (pid $wpid on .*) is gone" "$T/k2.log"
check "kill worker: job file in done/" [ -f "$Q/done/slow.yaml" ]
check "kill worker: image equals a plain render" cmp -s "$T/plain/slow/slow.png" "$Q/done/slow/slow.png"
check "kill worker: sidecar written" [ -s "$Q/done/slow/slow.json" ]
check "kill worker: running/ is empty" [ -z "$(ls -A "$Q/running")" ]
check "kill worker: no temporary files in done/" [ -z "$(ls -A "$Q/done/slow" | grep tmp)" ]

# 2c. a worker killed just after its claim, while writing the lease, leaves the lease's temporary
#     file in running/ (most of the time: the fsync is the slow part); once older than the lease
#     timeout it is a dead writer's and the next scan removes it; a fresh one is left alone
Q=$T/q2c; mkdir -p "$Q/running"
: >"$Q/running/.gone.yaml.lease.tmp.Ab12Cd"; touch -d '-2 minutes' "$Q/running/.gone.yaml.lease.tmp.Ab12Cd"
: >"$Q/running/.busy.yaml.lease.tmp.Ef34Gh"
"$WORKER" --queue "$Q" --once --quiet 2>/dev/null
check "dead lease temporary: removed" [ ! -e "$Q/running/.gone.yaml.lease.tmp.Ab12Cd" ]
check "fresh lease temporary: kept" [ -e "$Q/running/.busy.yaml.lease.tmp.Ef34Gh" ]

# 2a. a render process whose worker was killed stops at once, not after its row: one row of a
#     30000-pixel image at 10000 samples per pixel takes many seconds
Q=$T/q2a; mkdir -p "$Q"
printf 'scene: %s/scenes/checker.yaml\nwidth: 30000\nheight: 1\nthreshold: 1\nprocesses: 1\n' "$root" >"$Q/wide.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>/dev/null & wpid=$!
child=$(render_child "$wpid")
check "wide row: found the render process" [ -n "$child" ]
kill -9 "$wpid"; wait "$wpid" 2>/dev/null
check "wide row: the render process dies with its worker" gone "$child"
[ -n "$child" ] && kill -9 "$child" 2>/dev/null

# 2b. the same while another worker is already polling the queue: that one takes the job over
Q=$T/q2b; mkdir -p "$Q"; slow "$Q/slow.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>/dev/null & apid=$!
child=$(render_child "$apid")
# stopped, the render cannot finish within the poller's wait however fast the machine; the worker's
# death still kills it (PR_SET_PDEATHSIG sends SIGKILL, which a stopped process also takes)
[ -n "$child" ] && kill -STOP "$child"
"$WORKER" --queue "$Q" --quiet --poll 0.2 2>"$T/b2.log" & bpid=$!
sleep 0.5
check "poller: found the render process" [ -n "$child" ]
check "poller: idle while the claim is alive" [ -f "$Q/running/slow.yaml" ]
kill -9 "$apid"; wait "$apid" 2>/dev/null
check "poller: the stopped render process dies with its worker" gone "$child"
for _ in $(seq 1 300); do [ -f "$Q/done/slow.yaml" ] && break; sleep 0.05; done
kill -TERM "$bpid"; wait "$bpid"; rc=$?
check "poller: took over the dead worker's job" [ -f "$Q/done/slow.yaml" ]
check "poller: image equals a plain render" cmp -s "$T/plain/slow/slow.png" "$Q/done/slow/slow.png"
check "poller: exits 0 on SIGTERM when idle (got $rc)" [ "$rc" -eq 0 ]
check "poller: said it took the claim back" grep -q "slow.yaml: returned to the queue: its worker (pid $apid " "$T/b2.log"

# 3. kill -9 a render process: the job is retried and succeeds
Q=$T/q3; mkdir -p "$Q"; slow "$Q/crash.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/c.log" & wpid=$!
child=$(render_child "$wpid")
[ -n "$child" ] && kill -9 "$child"
wait "$wpid"; rc=$?
check "kill child: found a render process" [ -n "$child" ]
check "kill child: exit 0 after the retry (got $rc)" [ "$rc" -eq 0 ]
check "kill child: the retry is announced with the signal" grep -q "killed by signal 9.*retrying (attempt 2 of 2)" "$T/c.log"
check "kill child: job file in done/" [ -f "$Q/done/crash.yaml" ]
check "kill child: image equals a plain render" cmp -s "$T/plain/slow/slow.png" "$Q/done/crash/crash.png"
check "kill child: nothing in failed/" [ "$(count "$Q/failed/*")" -eq 0 ]

# 4. the same with --retries 0: failed/ with a log naming the signal
Q=$T/q4; mkdir -p "$Q"; slow "$Q/crash.yaml"
"$WORKER" --queue "$Q" --once --quiet --retries 0 2>"$T/c0.log" & wpid=$!
child=$(render_child "$wpid")
[ -n "$child" ] && kill -9 "$child"
wait "$wpid"; rc=$?
check "retries 0: exit 1 (got $rc)" [ "$rc" -eq 1 ]
check "retries 0: job file in failed/" [ -f "$Q/failed/crash.yaml" ]
check "retries 0: log names the signal" grep -q "^signal: 9 " "$Q/failed/crash.log"
check "retries 0: log has the error" grep -q "^error: .*killed by signal 9" "$Q/failed/crash.log"
check "retries 0: log counts one attempt" grep -q "^attempts: 1\$" "$Q/failed/crash.log"
check "retries 0: no image" [ ! -e "$Q/done/crash/crash.png" ]
check "retries 0: no empty done/crash/ folder" [ ! -e "$Q/done/crash" ]
check "retries 0: running/ is empty" [ -z "$(ls -A "$Q/running")" ]

# 5. a bad job goes to failed/ with its file:line:col, and the worker carries on
Q=$T/q5; mkdir -p "$Q"
printf 'scene: %s/scenes/checker.yaml\nwidth: 16\nthreshold: abc\n' "$root" >"$Q/bad.yaml"
tiny "$Q/good.yaml"
touch -d '-1 minute' "$Q/bad.yaml" # the older one is taken first
"$WORKER" --queue "$Q" --once --quiet 2>"$T/b.log"; rc=$?
check "bad job: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "bad job: in failed/" [ -f "$Q/failed/bad.yaml" ]
check "bad job: log has file:line:col" grep -Fq "error: $Q/bad.yaml:3:12: threshold: must be a number in (0, 100], got \"abc\"" "$Q/failed/bad.log"
check "bad job: stderr has file:line:col" grep -Fq "$Q/bad.yaml:3:12: threshold:" "$T/b.log"
check "bad job: the next job is done" [ -f "$Q/done/good.yaml" ]
check "bad job: the next job's image" [ -s "$Q/done/good/good.png" ]
check "bad job: nothing rendered for it" [ ! -e "$Q/done/bad" ]

# 6. SIGTERM mid-render: children stopped, the job back in the queue, exit 0
Q=$T/q6; mkdir -p "$Q"; slow "$Q/term.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/t.log" & wpid=$!
child=$(render_child "$wpid")
kill -TERM "$wpid"; wait "$wpid"; rc=$?
check "SIGTERM: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "SIGTERM: job back in the queue" [ -f "$Q/term.yaml" ]
check "SIGTERM: running/ is empty" [ -z "$(ls -A "$Q/running")" ]
check "SIGTERM: no job file in done/" [ ! -e "$Q/done/term.yaml" ]
check "SIGTERM: no image in done/" [ "$(count "$Q/done/term/*")" -eq 0 ]
check "SIGTERM: render process stopped" gone "$child"
check "SIGTERM: says so" grep -q "term.yaml: stopped by signal 15, returned to the queue" "$T/t.log"
# SIGTERM to the whole process group (a terminal's Ctrl-C, Slurm's scancel): the render processes
# ignore it and the worker stops them; never mistaken for a crash, even with --retries 0
setsid "$WORKER" --queue "$Q" --once --quiet --retries 0 2>"$T/tg.log" & wpid=$!
child=$(render_child "$wpid")
kill -TERM "-$wpid"; wait "$wpid"; rc=$?
check "group SIGTERM: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "group SIGTERM: job back in the queue" [ -f "$Q/term.yaml" ]
check "group SIGTERM: nothing in failed/" [ "$(count "$Q/failed/*")" -eq 0 ]
check "group SIGTERM: render process stopped" gone "$child"
# a second signal kills at once; the job is not lost (waiting or claimed for recovery)
"$WORKER" --queue "$Q" --once --quiet 2>/dev/null & wpid=$!
render_child "$wpid" >/dev/null
kill -INT "$wpid"; kill -TERM "$wpid"; wait "$wpid"; rc=$?
check "two signals: killed at once (got $rc)" [ "$rc" -gt 128 ]
check "two signals: the job is not lost" sh -c "[ -f '$Q/term.yaml' ] || [ -f '$Q/running/term.yaml' ]"

# 6a. SIGTERM while another worker holds the claim's recovery lock (it judged our lease dead and
#     is returning the claim): the stopped worker leaves the claim and that lock alone (it used to
#     return the job itself and delete the other's lock)
Q=$T/q6a; mkdir -p "$Q"; slow "$Q/locked.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/locked.log" & wpid=$!
render_child "$wpid" >/dev/null
: >"$Q/running/locked.yaml.lock"
kill -TERM "$wpid"; wait "$wpid"; rc=$?
check "held lock: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "held lock: the other's lock kept" [ -e "$Q/running/locked.yaml.lock" ]
check "held lock: the claim left in running/" [ -f "$Q/running/locked.yaml" ]
check "held lock: says so" grep -q "locked.yaml: stopped by signal 15; its recovery lock is held" "$T/locked.log"
rm -f "$Q/running/locked.yaml.lock" # the other recoverer gave up: the next worker recovers it
"$WORKER" --queue "$Q" --once --quiet 2>/dev/null; rc=$?
check "held lock: recovered and done afterwards (exit $rc)" [ -f "$Q/done/locked.yaml" ]

# 6b. a job of the same file name re-submitted while the first one renders, then the worker is
#     stopped: the first cannot go back without replacing the second, so it stays claimed and the
#     next worker takes it over in place; both are rendered, the first first (it used to stay
#     stuck in running/ for ever, blocking the second)
Q=$T/q6b; mkdir -p "$Q"; slow "$Q/again.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/again1.log" & wpid=$!
render_child "$wpid" >/dev/null
tiny "$Q/again.yaml" "seed: 7"
kill -TERM "$wpid"; wait "$wpid"; rc=$?
check "re-submitted: the stopped worker exits 0 (got $rc)" [ "$rc" -eq 0 ]
check "re-submitted: it says why the claim stays" grep -q "a newer again.yaml waits in the queue" "$T/again1.log"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/again2.log"; rc=$?
check "re-submitted: the next worker exits 0 (got $rc)" [ "$rc" -eq 0 ]
check "re-submitted: it took the stopped claim over" grep -q "again.yaml: taken over in $Q/running/" "$T/again2.log"
check "re-submitted: both rendered, the older first" \
    sh -c "grep -oE '^$TS again.yaml: again: [0-9x]*' '$T/again2.log' | sed 's/^.* again.yaml: //' | tr '\n' ' ' |
           grep -qx 'again: 64x64 again: 16x16 '"
check "re-submitted: running/ is empty" [ -z "$(ls -A "$Q/running")" ]
check "re-submitted: nothing waits" [ "$(count "$Q/*.yaml")" -eq 0 ]
check "re-submitted: done/ holds the newer job" grep -q "^seed: 7" "$Q/done/again.yaml"

# 7. leases of other hosts: kept while fresh, recovered once older than --lease-timeout;
#    a live pid on this host keeps its claim
Q=$T/q7; mkdir -p "$Q/running"
tiny "$Q/running/far.yaml"
printf 'host elsewhere.example\npid 1\nstart 0\ntoken elsewhere:1:0\n' >"$Q/running/far.yaml.lease"
touch -d '-10 seconds' "$Q/running/far.yaml.lease"
tiny "$Q/running/near.yaml"
printf 'host %s\npid %s\nstart 0\ntoken near:1:0\n' "$(uname -n)" "$$" >"$Q/running/near.yaml.lease"
# this hostname, a dead pid, but another pid space (a container with the host's name): its pid
# means nothing here, so its fresh lease keeps the claim (it used to be taken as "gone")
tiny "$Q/running/box.yaml"
printf 'host %s\npid %s\nstart 0\ntoken box:1:0\npids another-boot:pid:[1]\n' "$(uname -n)" \
    "$(sh -c 'echo $$')" >"$Q/running/box.yaml.lease"
touch -d '-10 seconds' "$Q/running/box.yaml.lease"
"$WORKER" --queue "$Q" --once --quiet --lease-timeout 60 2>/dev/null
check "fresh lease of another pid space on this host: kept" [ -f "$Q/running/box.yaml" ]
check "fresh lease of another host: kept" [ -f "$Q/running/far.yaml" ]
check "live pid on this host: kept" [ -f "$Q/running/near.yaml" ]
"$WORKER" --queue "$Q" --once --quiet --lease-timeout 5 2>"$T/far.log"
check "old lease of another host: recovered and done" [ -s "$Q/done/far/far.png" ]
check "old lease of another host: job file in done/" [ -f "$Q/done/far.yaml" ]
check "old lease: the reason names the host" grep -q "pid 1 on elsewhere.example) has not renewed the lease for 1[0-9] s" "$T/far.log"
check "live pid on this host: still kept" [ -f "$Q/running/near.yaml" ]
check "old lease of another pid space: recovered and done" [ -s "$Q/done/box/box.png" ]

# 7b. a --lease-timeout under a second: the holder renews its lease often enough (a quarter of the
#     timeout) that a polling worker never takes a live claim for a dead one and renders it again
Q=$T/q7b; mkdir -p "$Q"
{ slow /dev/stdout; echo "max_depth: 100"; } | sed 's/threshold: 3/threshold: 2/' >"$Q/short.yaml"
"$WORKER" --queue "$Q" --once --quiet --lease-timeout 0.8 2>"$T/short1.log" & apid=$!
render_child "$apid" >/dev/null
"$WORKER" --queue "$Q" --quiet --poll 0.1 --lease-timeout 0.8 2>"$T/short2.log" & bpid=$!
wait "$apid"; rc=$?
kill -TERM "$bpid"; wait "$bpid"
check "short lease: the holder exits 0 (got $rc)" [ "$rc" -eq 0 ]
check "short lease: its claim was never taken over" [ ! -s "$T/short2.log" ]
check "short lease: the holder filed it in done/" [ -f "$Q/done/short.yaml" ]

# 7c. a worker stopped (SIGSTOP: hung) past --lease-timeout loses its claim; another renders the
#     job and files it; when the first resumes it writes nothing over the new holder's outputs
Q=$T/q7c; mkdir -p "$Q"; slow "$Q/hung.yaml"
"$WORKER" --queue "$Q" --once --quiet --lease-timeout 1 2>"$T/hung1.log" & apid=$!
render_child "$apid" >/dev/null
kill -STOP "$apid"
"$WORKER" --queue "$Q" --quiet --poll 0.1 --lease-timeout 1 2>/dev/null & bpid=$!
for _ in $(seq 1 200); do [ -f "$Q/done/hung.yaml" ] && break; sleep 0.1; done
kill -TERM "$bpid"; wait "$bpid"
cp "$Q/done/hung/hung.json" "$T/hung-b.json" 2>/dev/null
kill -CONT "$apid"; wait "$apid"; rc=$?
check "hung worker: the other filed the job" [ -f "$Q/done/hung.yaml" ]
check "hung worker: exits 0 once resumed (got $rc)" [ "$rc" -eq 0 ]
check "hung worker: says the claim was taken over" grep -q "hung.yaml: the claim was taken over" "$T/hung1.log"
check "hung worker: wrote nothing over the new holder's sidecar" cmp -s "$T/hung-b.json" "$Q/done/hung/hung.json"
check "hung worker: the image equals a plain render" cmp -s "$T/plain/slow/slow.png" "$Q/done/hung/hung.png"

# 8. order: higher priority first, then oldest first
Q=$T/q8; mkdir -p "$Q"
tiny "$Q/old.yaml"; tiny "$Q/mid.yaml"; tiny "$Q/new.yaml" "priority: 5"; tiny "$Q/low.yaml" "priority: -1"
touch -d '-40 seconds' "$Q/low.yaml"; touch -d '-30 seconds' "$Q/old.yaml"
touch -d '-20 seconds' "$Q/mid.yaml"; touch -d '-10 seconds' "$Q/new.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/order.log"
order=$(grep -oE "^$TS [a-z]*\.yaml: [a-z]*: 16x16" "$T/order.log" | sed -E 's/^[^ ]* ([a-z]*)\.yaml: .*/\1/' | tr '\n' ' ')
check "order: priority, then age (got '$order')" [ "$order" = "new old mid low " ]

# 9. a claimed job still resolves its scene and reference beside DIR, not running/
Q=$T/q9/queue; mkdir -p "$Q" "$T/q9/scenes"
cp "$root/scenes/checker.yaml" "$T/q9/scenes/"
cp "$Q/../../q8/done/old/old.png" "$T/q9/ref.png"
printf 'scene: ../scenes/checker.yaml\nreference: ../ref.png\nwidth: 16\nheight: 16\nthreshold: 50\nlight_threshold: 50\n' >"$Q/rel.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/rel.log"; rc=$?
check "relative paths: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "relative paths: done" [ -s "$Q/done/rel/rel.png" ]
check "relative paths: scored against the reference" grep -q '"psnr"' "$Q/done/rel/rel.json"
check "relative paths: sidecar names the queued job file" grep -Fq "\"job_file\": \"$Q/rel.yaml\"" "$Q/done/rel/rel.json"

# 9b. odd entries in DIR: job files that are symbolic links (relative and absolute targets) render
#     (a relative target is seen from DIR, where the link was made, also once the claim moved the
#     link into running/); a directory named x.yaml and a dangling link are filed in failed/ with
#     a log (issue 21: they used to lie in DIR for ever, unsaid); a name
#     with spaces renders
Q=$T/q9b/queue; mkdir -p "$Q" "$T/q9b/store"
tiny "$T/q9b/store/real.yaml"
ln -s ../store/real.yaml "$Q/rel.yaml"; ln -s "$T/q9b/store/real.yaml" "$Q/abs.yaml"
ln -s nowhere.yaml "$Q/dangling.yaml"; mkdir "$Q/dir.yaml"; tiny "$Q/with space.yaml"
latin1=$(printf 'caf\351') # "café" in Latin-1: not UTF-8
tiny "$Q/$latin1.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/odd.log"; rc=$?
check "odd entries: exit 2, for the two that cannot run (got $rc)" [ "$rc" -eq 2 ]
check "odd entries: relative symlink rendered" [ -s "$Q/done/rel/rel.png" ]
check "odd entries: absolute symlink rendered" [ -s "$Q/done/abs/abs.png" ]
check "odd entries: name with spaces rendered" [ -s "$Q/done/with space/with space.png" ]
check "odd entries: a Latin-1 name rendered" [ -s "$Q/done/$latin1/$latin1.png" ]
check "odd entries: its sidecar is UTF-8 (the byte as U+FFFD)" \
    sh -c "! LC_ALL=C grep -q \"\$(printf '\\351')\" '$Q/done/$latin1/$latin1.json' &&
           grep -Fq '\"job\": \"caf\\ufffd\"' '$Q/done/$latin1/$latin1.json'"
check "odd entries: only those two failed" [ "$(ls "$Q/failed" | grep -c 'yaml$')" -eq 2 ]
check "odd entries: the directory filed in failed/ with a log" eval '[ -d "$Q/failed/dir.yaml" ] && [ -s "$Q/failed/dir.log" ]'
check "odd entries: the dangling link filed in failed/ with a log" eval '[ -L "$Q/failed/dangling.yaml" ] &&
    [ -s "$Q/failed/dangling.log" ]'
check "odd entries: the link's target untouched" [ -s "$T/q9b/store/real.yaml" ]
check "odd entries: the log names the worker that filed it (pid and host)" \
    grep -Eq '^worker: pid [1-9][0-9]* on [^ ]+$' "$Q/failed/dir.log"
# only unrunnable entries: a --once worker says it filed them, not just "nothing to do"
Q=$T/q9d; mkdir -p "$Q/d.yaml"
"$WORKER" --queue "$Q" --once 2>"$T/q9d.log"
check "only unrunnable entries: the closing line says they went to failed/ ($(tail -n 1 "$T/q9d.log"))" \
    grep -q 'nothing to do (what could not run was moved to failed/)' "$T/q9d.log"

# 9c. a file name holding a newline: every message stays one line (control characters escaped)
Q=$T/q9c; mkdir -p "$Q"
nl='
'
printf 'width: abc\n' >"$Q/bad${nl}name.yaml"; tiny "$Q/good${nl}name.yaml"
touch -d '-1 minute' "$Q/bad${nl}name.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/nl.log"; rc=$?
check "newline in a name: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "newline in a name: the good one rendered" [ -s "$Q/done/good${nl}name/good${nl}name.png" ]
# two claims, the error and its filing, the summary
check "newline in a name: five lines on stderr (got $(wc -l <"$T/nl.log"))" [ "$(wc -l <"$T/nl.log")" -eq 5 ]
check "newline in a name: escaped as backslash n" grep -Fq 'bad\nname.yaml: invalid job, moved to' "$T/nl.log"
check "newline in a name: the summary line escaped" grep -Fq 'good\nname: 16x16' "$T/nl.log"

# 9d. a queue that cannot be written (a read-only mount; without root, a folder without write
#     permission): the claim fails, said in one line, exit 2; a worker that idled silently and
#     exited 0 with the jobs still waiting was taken for an empty queue
Q=$T/q9d; mkdir -p "$Q/running" "$Q/done" "$Q/failed"; tiny "$Q/stuck.yaml"
ro=""
if mkdir -p "$T/q9d-ro" && mount --bind "$Q" "$T/q9d-ro" 2>/dev/null; then
    if mount -o remount,bind,ro "$T/q9d-ro" 2>/dev/null; then ro="$T/q9d-ro"; else umount "$T/q9d-ro"; fi
elif [ "$(id -u)" != 0 ]; then
    chmod 555 "$Q" "$Q/running"; ro=$Q
fi
if [ -n "$ro" ]; then
    "$WORKER" --queue "$ro" --once --quiet 2>"$T/ro.log"; rc=$?
    check "read-only queue: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "read-only queue: one line says why" \
        sh -c "[ \$(wc -l <'$T/ro.log') -eq 1 ] && grep -q 'cannot claim stuck.yaml into .*running/: ' '$T/ro.log'"
    timeout 20 "$WORKER" --queue "$ro" --poll 0.1 --quiet 2>/dev/null; rc=$? # it idled for ever
    check "read-only queue: a polling worker exits 2 too (got $rc)" [ "$rc" -eq 2 ]
    check "read-only queue: the job still waits" [ -f "$Q/stuck.yaml" ]
    if [ "$ro" = "$Q" ]; then chmod 755 "$Q" "$Q/running"; else umount "$ro"; fi
else
    skip "read-only queue: no read-only mount possible here"
fi

# 10. usage errors
"$WORKER" --queue "$T/nowhere" --once 2>"$T/u.log"; rc=$?
check "missing queue dir: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "missing queue dir: named" grep -q "nowhere: No such file" "$T/u.log"
"$WORKER" --queue "$T/q8" --retries -1 2>/dev/null; rc=$?
check "bad --retries: exit 2 (got $rc)" [ "$rc" -eq 2 ]
# --out does nothing with --queue (outputs go to DIR/done/) and --once nothing without it: both say so
Q2="$T/qout"; mkdir -p "$Q2"; tiny "$Q2/one.yaml"
"$WORKER" --queue "$Q2" --once --quiet --out "$T/elsewhere" 2>"$T/qout.err"; rc=$?
check "--queue with --out: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "--queue with --out: rendered into DIR/done/" [ -s "$Q2/done/one/one.png" ]
check "--queue with --out: nothing in --out" [ ! -e "$T/elsewhere" ]
check "--queue with --out: one line says --out is ignored" \
    sh -c "grep -c -- '--out is ignored with --queue' '$T/qout.err' | grep -qx 1"
tiny "$T/solo.yaml"
"$WORKER" --once --quiet --out "$T/solo-out" "$T/solo.yaml" 2>"$T/solo.err"; rc=$?
check "--once without --queue: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "--once without --queue: the job renders" [ -s "$T/solo-out/solo/solo.png" ]
check "--once without --queue: one line says it is ignored" \
    sh -c "grep -c -- '--once is ignored without --queue' '$T/solo.err' | grep -qx 1"
finish
