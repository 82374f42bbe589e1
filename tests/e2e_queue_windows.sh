#!/bin/sh
# End to end: issue 21's remaining race windows in the queue, widened on purpose by an LD_PRELOAD
# shim (tests/shim/race.c: a kill -9, a SIGSTOP or another worker's claim at one chosen rename) so
# that they are hit every time.
. tests/lib.sh
root=$(pwd)

tiny() { # tiny FILE SIZE [SEED]: a SIZExSIZE job that renders in a few milliseconds
    { echo "scene: $root/scenes/checker.yaml"; echo "width: $2"; echo "height: $2"; echo "threshold: 50"
      echo "light_threshold: 50"; echo "processes: 1"; echo "seed: ${3:-1}"; } >"$1"
}
temps() { find "$1" -name '.*.tmp.*' | wc -l; }

need_shim race

# defect 7: a finished job is filed in done/ and, that instant, another worker claims a re-queued
# file of the same name: the new claim's lease must survive the filing of the old one
Q=$T/q7; mkdir -p "$Q"
tiny "$Q/x.yaml" 16
sleep 60 & live=$!
lease_text "$live" 7 >"$T/lease7"
SHIM_REQUEUE=$T/lease7 LD_PRELOAD=$T/race.so "$WORKER" --queue "$Q" --once 2>"$T/q7.log"; rc=$?
check "7: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "7: the first x.yaml is done" [ -f "$Q/done/x.yaml" ]
check "7: the new claim of x.yaml keeps its lease" grep -q "token .*:$live:7" "$Q/running/x.yaml.lease"
kill "$live" 2>/dev/null; wait "$live" 2>/dev/null

# defect 8: a writer killed half-way left its temporaries in done/<name>/; the job, run again, ends
# in failed/ (its reference is another size): they go with it, whatever wrote them
Q=$T/q8; mkdir -p "$Q"
tiny "$Q/y.yaml" 16
SHIM_KILL_TO=.json LD_PRELOAD=$T/race.so "$WORKER" --queue "$Q" --once 2>"$T/q8a.log"
check "8: the writer was killed with temporaries left" [ "$(temps "$Q/done/y")" -gt 0 ]
"$WORKER" "$root/jobs/checker.yaml" --out "$T/ref8" --quiet 2>/dev/null
echo "reference: $(ls "$T"/ref8/*/*.png | head -n 1)" >>"$Q/running/y.yaml"
"$WORKER" --queue "$Q" --once 2>"$T/q8b.log"
check "8: the job ended in failed/" [ -f "$Q/failed/y.yaml" ]
check "8: no temporary file left in done/y/" [ "$(temps "$Q/done")" -eq 0 ]
: >"$Q/done/y/.z.png.tmp.AbC123"
tiny "$Q/y.yaml" 16; echo "width: 0" >>"$Q/y.yaml"
"$WORKER" --queue "$Q" --once 2>"$T/q8c.log"
check "8: an invalid job's folder is cleaned too" [ "$(temps "$Q/done")" -eq 0 ]

# defect 6: a writer killed between the image's rename and the sidecar's never leaves a new image
# beside the old sidecar: the old sidecar goes first, so a reader sees the old pair, or an image
# without a sidecar (not finished: rendered again), or the new pair
O=$T/o6
tiny "$T/z.yaml" 16 1
"$WORKER" "$T/z.yaml" --out "$O" --quiet 2>/dev/null
tiny "$T/z.yaml" 16 2
SHIM_KILL_TO=.json LD_PRELOAD=$T/race.so "$WORKER" "$T/z.yaml" --out "$O" --quiet 2>/dev/null
check "6: killed before the sidecar's rename: no sidecar of another render" \
    sh -c '[ ! -e "$1" ] || grep -q "\"seed\": 2" "$1"' - "$O/z/z.json"
"$WORKER" "$T/z.yaml" --out "$O" 2>"$T/o6.log"
check "6: the next run renders it again" grep -q "16x16" "$T/o6.log"
check "6: then the pair agrees" grep -q '"seed": 2' "$O/z/z.json"

# defect 3: a worker stopped (SIGSTOP) while it holds its output folder's lock, its claim taken
# over: the new holder waits for the lock no longer than a lease timeout, writes, and files the job;
# the stopped one, resumed, sees before renaming anything that the claim is no longer its own and
# writes nothing
Q=$T/q3; mkdir -p "$Q"
tiny "$Q/s.yaml" 16
SHIM_STOP_STAGE=.json.tmp. LD_PRELOAD=$T/race.so "$WORKER" --queue "$Q" --once --lease-timeout 2 \
    2>"$T/q3a.log" & a=$!
for _ in $(seq 1 500); do
    [ "$(ps -o stat= -p "$a" | cut -c1)" = T ] && break
    sleep 0.02
done
check "3: the first worker stopped holding the lock" [ "$(ps -o stat= -p "$a" | cut -c1)" = T ]
sleep 3
timeout 20 "$WORKER" --queue "$Q" --once --lease-timeout 2 2>"$T/q3b.log"; rc=$?
check "3: the new holder is not blocked by the stopped one (exit $rc)" [ "$rc" -eq 0 ]
check "3: it filed the job in done/" [ -f "$Q/done/s.yaml" ]
check "3: saying it wrote without the lock" grep -q "writing without it" "$T/q3b.log"
ino=$(ls -i "$Q/done/s/s.png" 2>/dev/null | cut -d' ' -f1)
kill -CONT "$a"; wait "$a"
check "3: the resumed worker wrote nothing over the new holder's image" \
    eval '[ -n "$ino" ] && [ "$(ls -i "$Q/done/s/s.png" | cut -d" " -f1)" = "$ino" ]'
check "3: and said why" grep -q "taken over" "$T/q3a.log"
check "3: no temporary file left" [ "$(temps "$Q/done")" -eq 0 ]
check "3: the pair agrees" grep -q '"seed": 1' "$Q/done/s/s.json"

finish
