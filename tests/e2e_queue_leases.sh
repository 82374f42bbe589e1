#!/bin/sh
# Hostile leases (issue 27, items 2 and 9): a FIFO, or a link to /dev/zero, at running/X.yaml.lease
# neither hangs nor spins `worker status` or a worker (leases are regular files, opened
# non-blocking without following links, bounded in size); a lease's fields are shown sanitised
# (no terminal escapes, no absurd elapsed or percent); an unreadable failed/ is an error for
# status and requeue --failed.
. tests/lib.sh
root=$(pwd)
tiny() { printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nthreshold: 50\nlight_threshold: 50\nprocesses: 1\n' "$root" >"$1"; }
within() { # within SECONDS CMD...: run CMD, killed after SECONDS; its exit status, 124 when killed
    timeout -s KILL "$@"; rc=$?; [ "$rc" -eq 137 ] && rc=124; return "$rc"
}
for kind in fifo zero; do
    Q=$T/q-$kind; mkdir -p "$Q/running"
    tiny "$Q/running/x.yaml"
    if [ "$kind" = fifo ]; then mkfifo "$Q/running/x.yaml.lease"; else ln -s /dev/zero "$Q/running/x.yaml.lease"; fi
    tiny "$Q/y.yaml"
    within 10 "$WORKER" status "$Q" >"$T/st-$kind.txt" 2>&1; rc=$?
    check "$kind lease: status ends at once (rc $rc)" [ "$rc" -eq 0 ]
    check "... shows the claim without a lease" grep -q 'x.yaml  (no lease yet)' "$T/st-$kind.txt"
    within 20 "$WORKER" --queue "$Q" --once --quiet --lease-timeout 1 >/dev/null 2>"$T/w-$kind.log"; rc=$?
    check "$kind lease: a worker drains the queue (rc $rc): $(cat "$T/w-$kind.log")" eval '[ "$rc" -ne 124 ] && [ -f "$Q/done/y.yaml" ]'
done

# a forged lease: escapes in the host, absurd numbers
Q=$T/q-forged; mkdir -p "$Q/running"
tiny "$Q/running/f.yaml"
printf 'host evil\033[2Jhost\npid 999999999\nstart 9223372036854775807\ntoken t\nprogress 2147483647 10 -5 99999 -3\n' >"$Q/running/f.yaml.lease"
"$WORKER" status "$Q" >"$T/forged.txt" 2>&1
check "forged lease: no escape byte printed" [ -z "$(tr -d '\n' <"$T/forged.txt" | tr -d '[:print:]')" ]
check "forged lease: elapsed unknown, percent sane: $(grep f.yaml "$T/forged.txt")" \
    grep -q 'f.yaml  host evil?\[2Jhost  pid 999999999  attempt 0  0% (0/10 rows)  elapsed --  ETA --' "$T/forged.txt"

# failed/ that cannot be read (a file in its place: root reads any folder)
Q=$T/q-bad; mkdir -p "$Q"; : >"$Q/failed"
"$WORKER" status "$Q" >"$T/bad.txt" 2>&1; rc=$?
check "unreadable failed/: status fails (rc $rc): $(cat "$T/bad.txt")" eval '[ "$rc" -eq 2 ] && grep -q "failed: cannot be read" "$T/bad.txt"'
"$WORKER" requeue "$Q" --failed >"$T/rq.txt" 2>&1; rc=$?
check "unreadable failed/: requeue --failed fails (rc $rc): $(cat "$T/rq.txt")" [ "$rc" -eq 2 ]

# requeue removes the log written under the file's stem (a job that did not load), and the loser
# of a race names it
Q=$T/q-log; mkdir -p "$Q"
printf 'name: named\nwidth: oops\n' >"$Q/s.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>/dev/null
check "the invalid job's log is failed/s.log" [ -f "$Q/failed/s.log" ]
"$WORKER" requeue "$Q" s 2>/dev/null
check "requeue removed failed/s.log" eval '[ ! -f "$Q/failed/s.log" ] && [ -f "$Q/s.yaml" ]'
# two requeues racing for one failed file: the first stops (SIGSTOP, by the shim) just before its
# rename, the second moves the file; the first, continued, names what happened
if preload_shim race; then
    Q=$T/q-race; mkdir -p "$Q"
    printf 'width: oops\n' >"$Q/r.yaml"
    "$WORKER" --queue "$Q" --once --quiet 2>/dev/null
    SHIM_STOP_TO="$Q/r.yaml" LD_PRELOAD=$T/race.so "$WORKER" requeue "$Q" r 2>"$T/race-a.txt" & a=$!
    for _ in $(seq 1 500); do [ "$(ps -o stat= -p "$a" | cut -c1)" = T ] && break; sleep 0.02; done
    "$WORKER" requeue "$Q" r 2>"$T/race-b.txt"; rcb=$?
    kill -CONT "$a"; wait "$a"; rca=$?
    check "racing requeues: the second moved it (rc $rcb)" eval '[ "$rcb" -eq 0 ] && [ -f "$Q/r.yaml" ]'
    check "racing requeues: the loser exits 2 and says why: $(cat "$T/race-a.txt")" \
        sh -c "[ $rca -eq 2 ] && grep -q 'no longer there: moved meanwhile' '$T/race-a.txt'"
    # the same race under --failed ("every failed job"): the file moved by the other requeue is
    # requeued all the same, so neither fails (issue 36, defect 11: both exited 2)
    "$WORKER" --queue "$Q" --once --quiet 2>/dev/null
    SHIM_STOP_TO="$Q/r.yaml" LD_PRELOAD=$T/race.so "$WORKER" requeue "$Q" --failed 2>"$T/race-c.txt" & a=$!
    for _ in $(seq 1 500); do [ "$(ps -o stat= -p "$a" | cut -c1)" = T ] && break; sleep 0.02; done
    "$WORKER" requeue "$Q" --failed 2>"$T/race-d.txt"; rcb=$?
    kill -CONT "$a"; wait "$a"; rca=$?
    check "racing requeue --failed: both exit 0 (got $rca, $rcb): $(cat "$T/race-c.txt")" \
        eval '[ "$rca" -eq 0 ] && [ "$rcb" -eq 0 ] && [ -f "$Q/r.yaml" ] && [ -z "$(ls "$Q/failed")" ]'
else
    skip "no C compiler for the shim tests/shim/race.c: racing requeues"
fi
# requeue --failed removes every failed job's log: under its stem, and under its name
Q=$T/q-logs; mkdir -p "$Q"
printf 'width: oops\n' >"$Q/s1.yaml"
printf 'name: other\nwidth: oops\n' >"$Q/s2.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>/dev/null
printf 'name: given\nscene: x.yaml\n' >"$Q/failed/s3.yaml"
printf 'job: %s/s3.yaml\nerror: a render failed\n' "$Q" >"$Q/failed/given.log"
"$WORKER" requeue "$Q" --failed 2>"$T/rqf.txt"; rc=$?
check "requeue --failed: exit 0 (got $rc), every log gone: $(ls "$Q/failed")" \
    eval '[ "$rc" -eq 0 ] && [ -z "$(ls "$Q/failed")" ] && [ "$(ls "$Q" | grep -c yaml)" -eq 3 ]'
finish
