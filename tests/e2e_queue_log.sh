#!/bin/sh
# End to end: a queue worker's log: every line starts with an ISO 8601 time (UTC) and names the job
# file it is about; one line says each claim; a warning when the workers on one host run more
# render processes than it has cores (counted from the leases in running/).
. tests/lib.sh
root=$(pwd)
TS='[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z'
cores=$(getconf _NPROCESSORS_ONLN)
tiny() { # tiny FILE [PROCESSES]
    { echo "scene: $root/scenes/checker.yaml"; echo "width: 16"; echo "height: 16"; echo "threshold: 50"
      echo "light_threshold: 50"; echo "processes: ${2:-1}"; } >"$1"
}

# a good job, a bad one and an unrunnable entry: every line timed and named
Q=$T/q1; mkdir -p "$Q"
tiny "$Q/a.yaml"; printf 'width: x\n' >"$Q/b.yaml"; mkdir "$Q/c.yaml"
"$WORKER" --queue "$Q" --once 2>"$T/q1.log"; rc=$?
check "log: exit 2 (a bad job) (got $rc)" [ "$rc" -eq 2 ]
check "log: every line timed and naming its job: $(cat "$T/q1.log")" \
    sh -c "[ \$(grep -cvE '^$TS [^ ]+\\.yaml: ' '$T/q1.log') -eq 0 ] && [ \$(grep -c . '$T/q1.log') -ge 5 ]"
check "log: one claim line per claimed job" \
    eval '[ "$(grep -cE "^$TS a\\.yaml: claimed by pid [0-9]+ on " "$T/q1.log")" -eq 1 ] &&
    [ "$(grep -cE "^$TS b\\.yaml: claimed by pid [0-9]+ on " "$T/q1.log")" -eq 1 ]'
check "log: the summary after the claim" grep -qE "^$TS a\\.yaml: a: 16x16 " "$T/q1.log"
check "log: the error at file:line:col" grep -qE "^$TS b\\.yaml: $Q/b\\.yaml:1:8: width: " "$T/q1.log"
check "log: no cores warning for $cores cores and one process" sh -c "! grep -q 'render processes on' '$T/q1.log'"

# another live worker on this host (a lease naming a live pid) runs as many render processes as
# there are cores: the next claim says the host is oversubscribed
Q=$T/q2; mkdir -p "$Q/running"
sleep 60 & live=$!
tiny "$Q/running/busy.yaml"
{ lease_text "$live"
  printf 'progress %10d %10d %12.1f %5d %5d\n' 1 16 0.1 1 "$cores"; } >"$Q/running/busy.yaml.lease"
tiny "$Q/d.yaml" 2
"$WORKER" --queue "$Q" --once 2>"$T/q2.log"; rc=$?
kill "$live" 2>/dev/null; wait "$live" 2>/dev/null
check "cores: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "cores: warned, with the counts: $(cat "$T/q2.log")" \
    grep -qE "^$TS d\\.yaml: warning: the workers on $(hostname) run $((cores + 2)) render processes on $cores cores \\(this job 2, others $cores\\)" "$T/q2.log"
check "cores: the job rendered all the same" [ -s "$Q/done/d/d.png" ]
check "cores: the other worker's claim untouched" [ -f "$Q/running/busy.yaml.lease" ]
finish
