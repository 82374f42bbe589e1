#!/bin/sh
# End to end: the queue's race windows, widened on purpose (an LD_PRELOAD shim, SIGSTOP) so that
# they are hit every time: a claim handed back never replaces a job queued meanwhile under its name.
. tests/lib.sh
root=$(pwd)

tiny() { # tiny FILE SIZE: a SIZExSIZE job that renders in a few milliseconds
    { echo "scene: $root/scenes/checker.yaml"; echo "width: $2"; echo "height: $2"; echo "threshold: 50"
      echo "light_threshold: 50"; echo "processes: 1"; } >"$1"
}
dead_pid() { sh -c 'echo $$'; }

need_shim arrive

# 1. a dead worker's claim is returned to DIR just as a new job of its file name arrives there:
#    the new file must survive (rename() replaced it), and both jobs render
Q=$T/q1; mkdir -p "$Q/running"
tiny "$Q/running/x.yaml" 16
lease_text "$(dead_pid)" >"$Q/running/x.yaml.lease"
tiny "$T/new.yaml" 24
SHIM_ARRIVE=$T/new.yaml LD_PRELOAD=$T/arrive.so "$WORKER" --queue "$Q" --once 2>"$T/q1.log"; rc=$?
check "return race: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "return race: the dead claim rendered (16x16)" grep -q "16x16" "$T/q1.log"
check "return race: the job queued meanwhile rendered too (24x24)" grep -q "24x24" "$T/q1.log"
check "return race: nothing left waiting or running" eval '[ ! -e "$Q/x.yaml" ] && [ -z "$(ls -A "$Q/running")" ]'
# 2. the same window on a stop signal's hand-back: the claim stays in running/ for the next worker
Q=$T/q2; mkdir -p "$Q"
{ echo "scene: $root/scenes/checker.yaml"; echo "width: 64"; echo "height: 64"; echo "threshold: 3"
  echo "light_threshold: 50"; echo "processes: 1"; } >"$Q/x.yaml"
SHIM_ARRIVE=$T/new.yaml LD_PRELOAD=$T/arrive.so "$WORKER" --queue "$Q" --once 2>"$T/q2.log" & wpid=$!
child=$(render_child "$wpid")
check "signal race: a render started" [ -n "$child" ]
kill -TERM "$wpid"; wait "$wpid"
check "signal race: the job queued meanwhile is kept" grep -q "width: 24" "$Q/x.yaml"
check "signal race: the stopped claim stays in running/" grep -q "width: 64" "$Q/running/x.yaml"
check "signal race: said so" grep -q "stays in" "$T/q2.log"
"$WORKER" --queue "$Q" --once 2>"$T/q2b.log"; rc=$?
check "signal race: the next worker renders both (got $rc)" eval '[ "$rc" -eq 0 ] && grep -q "64x64" "$T/q2b.log" &&
    grep -q "24x24" "$T/q2b.log"'
finish
