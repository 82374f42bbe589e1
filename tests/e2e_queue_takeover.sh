#!/bin/sh
# e2e_queue_takeover: a queue worker whose claim is taken over while it waits for its output
# folder's lock writes nothing: the claim is judged again under the lock, not only before it.
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/.." && pwd)

# waiting PID: the process sleeps in flock() (up to 10 s); 1 when /proc does not say
in_flock() {
    for _ in $(seq 1 200); do
        case "$(cat "/proc/$1/wchan" 2>/dev/null)" in *lock*) return 0 ;; esac
        sleep 0.05
    done
    return 1
}

tiny() { # tiny FILE: a 16x16 job that renders in a few milliseconds
    { echo "scene: $root/scenes/checker.yaml"; echo "width: 16"; echo "height: 16"; echo "threshold: 50"
      echo "light_threshold: 50"; echo "processes: 1"; } >"$1"
}

# 1. the claim is taken over (the lease rewritten) while the worker sleeps in flock()
Q=$T/q; mkdir -p "$Q/done/late"
tiny "$Q/late.yaml"
# hold the output folder's lock (released when a line arrives on the fifo; no child keeps it)
mkfifo "$T/release"
( flock 9; : >"$T/locked"; read -r _ <"$T/release" ) 9<"$Q/done/late" & lpid=$!
for _ in $(seq 1 200); do [ -f "$T/locked" ] && break; sleep 0.05; done
"$WORKER" --queue "$Q" --once --quiet --lease-timeout 60 2>"$T/late.log" & wpid=$!
in_flock "$wpid"
# meanwhile another worker (here: a live process of this host) took the claim over
printf 'host %s\npid %s\nstart 0\ntoken other:%s:0\n' "$(hostname)" "$$" "$$" >"$Q/running/late.yaml.lease"
echo >"$T/release"; wait "$lpid"
wait "$wpid"; rc=$?
check "taken over: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "taken over: says so" grep -q "late.yaml: the claim was taken over" "$T/late.log"
check "taken over: wrote no image" [ ! -e "$Q/done/late/late.png" ]
check "taken over: wrote no sidecar" [ ! -e "$Q/done/late/late.json" ]
check "taken over: left no staged file" [ -z "$(ls -A "$Q/done/late")" ]
check "taken over: the claim stays with its new holder" [ -f "$Q/running/late.yaml" ]

# 2. SIGTERM to a worker waiting for its output folder's lock (its holder hung) stops it there: the
#    claim goes back to the queue, nothing is written; it used to wait on, deaf to the signal
Q=$T/q2; mkdir -p "$Q/done/late"
tiny "$Q/late.yaml"
mkfifo "$T/release2"; rm -f "$T/locked"
( flock 9; : >"$T/locked"; read -r _ <"$T/release2" ) 9<"$Q/done/late" & lpid=$!
for _ in $(seq 1 200); do [ -f "$T/locked" ] && break; sleep 0.05; done
"$WORKER" --queue "$Q" --once --quiet 2>"$T/term.log" & wpid=$!
in_flock "$wpid"
kill -TERM "$wpid"
ended=0
for _ in $(seq 1 200); do kill -0 "$wpid" 2>/dev/null || { ended=1; break; }; sleep 0.05; done
check "SIGTERM while waiting for the folder's lock: the worker ends with the lock still held" [ "$ended" -eq 1 ]
echo >"$T/release2"; wait "$lpid"
wait "$wpid"
check "SIGTERM while waiting: the job is back in the queue" [ -f "$Q/late.yaml" ]
check "SIGTERM while waiting: says so" grep -q "late.yaml: stopped by signal 15, returned to the queue" "$T/term.log"
check "SIGTERM while waiting: wrote nothing" [ -z "$(ls -A "$Q/done/late")" ]

finish
