#!/bin/sh
# e2e_queue_cancel: a job file removed (or moved away) from DIR/running/ while its worker renders it
# cancels the render: the worker stops its render processes at its next lease renewal, writes
# nothing, says so in one line and goes on with the next job. And the lease is renewed while the
# worker waits outside the render (here: for its output folder's lock), so that a live claim is
# never taken by another worker.
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/.." && pwd)

long() { # long FILE: a job that renders for minutes, in 2 processes
    printf 'scene: %s/scenes/cornell.yaml\nwidth: 300\nthreshold: 1\nprocesses: 2\n' "$root" >"$1"
}
tiny() {
    printf 'scene: %s/scenes/checker.yaml\nwidth: 16\nthreshold: 50\nlight_threshold: 50\nprocesses: 1\n' "$root" >"$1"
}
ended() { # ended PID: wait up to 20 s for PID to end; 1 if it did not (then it is killed)
    for _ in $(seq 1 400); do kill -0 "$1" 2>/dev/null || return 0; sleep 0.05; done
    kill -9 "$1" 2>/dev/null; pkill -9 -P "$1" 2>/dev/null
    return 1
}

for how in rm mv; do
    Q=$T/q-$how; mkdir -p "$Q"
    long "$Q/long.yaml"; touch -d '1 hour ago' "$Q/long.yaml" 2>/dev/null
    tiny "$Q/next.yaml"
    "$WORKER" --queue "$Q" --once --quiet --lease-timeout 2 2>"$T/$how.log" & wpid=$!
    child=$(render_child "$wpid")
    check "$how: a render process started" [ -n "$child" ]
    if [ "$how" = rm ]; then rm "$Q/running/long.yaml"; else mv "$Q/running/long.yaml" "$T/away.yaml"; fi
    ended "$wpid"; gone=$?
    check "$how: the worker went on and ended (it rendered the cancelled job on)" [ "$gone" -eq 0 ]
    wait "$wpid"; rc=$?
    check "$how: exit 0 (got $rc)" [ "$rc" -eq 0 ]
    check "$how: its render process was stopped" sh -c "! kill -0 $child 2>/dev/null"
    check "$how: one line says so: $(cat "$T/$how.log")" \
        [ "$(grep -c 'long.yaml: .*running/long.yaml was removed or moved away while it rendered' "$T/$how.log")" -eq 1 ]
    check "$how: nothing written for it" [ ! -e "$Q/done/long" ]
    check "$how: not filed as failed" [ -z "$(ls -A "$Q/failed")" ]
    check "$how: no lease left behind" [ -z "$(ls -A "$Q/running")" ]
    check "$how: the next job rendered" [ -s "$Q/done/next/next.png" ]
done

# a compare job in a queue is spread over it as renders (DIR/spread/<stem>/): removing that folder
# while one renders cancels the study: the render stops, one line says so, nothing is written
Q=$T/q-cmp; mkdir -p "$Q"
printf 'scenes: [%s/scenes/cornell.yaml]\nwidth: 300\nvariants: [{ sampler: jitter, threshold: 1 }]\n' "$root" >"$Q/cmp.yaml"
"$WORKER" --queue "$Q" --once --quiet --lease-timeout 2 2>"$T/cmp.log" & wpid=$!
child=$(render_child "$wpid")
check "compare: its render runs from the study's folder" eval 'ls "$Q/spread/cmp/running" | grep -q "^b-img-0-00000.*yaml$"'
rm -r "$Q/spread/cmp"
ended "$wpid"
wait "$wpid"; rc=$?
check "compare: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "compare: one line says so: $(cat "$T/cmp.log")" grep -q 'b-img-0-00000[-p0-9]*.yaml: .*was removed while it rendered (cancelled)' "$T/cmp.log"
check "compare: nothing written" [ -z "$(find "$Q/done" -mindepth 1 ! -name .cache)" ]

# the lease is renewed while the worker waits for its output folder's lock: a second worker with
# the same lease timeout leaves the live claim alone
Q=$T/q-wait; mkdir -p "$Q/done/late"
tiny "$Q/late.yaml"
mkfifo "$T/release"
( flock 9; : >"$T/locked"; read -r _ <"$T/release" ) 9<"$Q/done/late" & lpid=$!
for _ in $(seq 1 200); do [ -f "$T/locked" ] && break; sleep 0.05; done
"$WORKER" --queue "$Q" --once --quiet --lease-timeout 0.5 2>"$T/a.log" & wpid=$!
for _ in $(seq 1 200); do [ -f "$Q/running/late.yaml.lease" ] && break; sleep 0.05; done
sleep 2 # four lease timeouts in the lock's wait
"$WORKER" --queue "$Q" --once --quiet --lease-timeout 0.5 2>"$T/b.log" & bpid=$!
ended "$bpid"; bgone=$?
echo >"$T/release"; wait "$lpid"
ended "$wpid"
wait "$wpid"; rc=$?
check "waiting for the lock: the second worker did not wait for it too" [ "$bgone" -eq 0 ]
check "waiting for the lock: the second worker took nothing: $(cat "$T/b.log")" [ ! -s "$T/b.log" ]
check "waiting for the lock: the first kept its claim: $(cat "$T/a.log")" sh -c "! grep -q 'taken over' '$T/a.log'"
check "waiting for the lock: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "waiting for the lock: the image written once the lock came" [ -s "$Q/done/late/late.png" ]
check "waiting for the lock: the job filed as done" [ -f "$Q/done/late.yaml" ]
finish
