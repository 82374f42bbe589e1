#!/bin/sh
# End to end: kill -9 storm. Several workers drain 30+ jobs while workers and render processes are
# killed at random (and replaced); then one last worker drains what is left. Every job ends in
# done/ or failed/ exactly once, no temporary, lease or lock file is left, and every image matches
# its sidecar and the plain render byte for byte. STRESS_JOBS and STRESS_SECONDS make it longer
# (`make stress`: 200 jobs for 300 s).
. tests/lib.sh
root=$(pwd)
jobs=${STRESS_JOBS:-32}
seconds=${STRESS_SECONDS:-12}
workers=3
job() {
    { echo "scene: $root/scenes/checker.yaml"; echo "width: 64"; echo "height: 64"; echo "threshold: 4"
      echo "light_threshold: 50"; echo "processes: 2"; echo "name: $2"; echo "output: img.png"; } >"$1"
}
rnd() { od -An -N2 -tu2 /dev/urandom | tr -d ' '; } # 0..65535

job "$T/ref.yaml" ref
"$WORKER" --quiet --out "$T/plain" "$T/ref.yaml" 2>/dev/null
check "plain render" [ -s "$T/plain/ref/img.png" ]

Q=$T/q; mkdir -p "$Q"
i=1; while [ "$i" -le "$jobs" ]; do job "$Q/j$i.yaml" "j$i"; i=$((i + 1)); done
start() { "$WORKER" --queue "$Q" --once --quiet --lease-timeout 2 --poll 0.1 --retries 1 >/dev/null 2>>"$T/workers.log" & echo $!; }
pids=""; n=0; while [ "$n" -lt "$workers" ]; do pids="$pids $(start)"; n=$((n + 1)); done
kills=0
end=$(($(date +%s) + seconds))
while [ "$(date +%s)" -lt "$end" ] && [ -n "$(ls "$Q" "$Q/running" | grep 'yaml$')" ]; do
    sleep 0.$(($(rnd) % 4 + 1))
    set -- $pids
    victim=$(eval echo "\${$(($(rnd) % $# + 1))}")
    if [ $(($(rnd) % 2)) -eq 0 ]; then
        child=$(pgrep -P "$victim" | head -n 1)
        [ -n "$child" ] && kill -9 "$child" 2>/dev/null && kills=$((kills + 1))
    else
        kill -9 "$victim" 2>/dev/null && kills=$((kills + 1))
    fi
    alive=""
    for p in $pids; do
        if kill -0 "$p" 2>/dev/null; then alive="$alive $p"; else alive="$alive $(start)"; fi
    done
    pids=$alive
done
for p in $pids; do # the workers are not this shell's children (started in $(...)): wait by polling
    while kill -0 "$p" 2>/dev/null; do sleep 0.1; done
done
echo "stress: $kills kills"
# a last worker, unharmed, takes up every dead claim and drains the rest
# (a claim whose worker died before writing its lease is dead once it is 2 s old: run again until
# nothing is left, 30 s at most)
for _ in $(seq 1 30); do
    "$WORKER" --queue "$Q" --once --quiet --lease-timeout 2 2>>"$T/workers.log"
    [ -z "$(ls -A "$Q/running")" ] && [ -z "$(ls "$Q" | grep 'yaml$')" ] && break
    sleep 1
done
check "drained: nothing waiting" [ -z "$(ls "$Q" | grep 'yaml$')" ]
check "drained: running/ is empty (no claim, lease, lock or temporary)" [ -z "$(ls -A "$Q/running")" ]
once=0 both=0 imgs=0 same=0
i=1; while [ "$i" -le "$jobs" ]; do
    d=0; f=0; [ -f "$Q/done/j$i.yaml" ] && d=1; [ -f "$Q/failed/j$i.yaml" ] && f=1
    [ $((d + f)) -eq 1 ] && once=$((once + 1))
    [ $((d + f)) -eq 2 ] && both=$((both + 1))
    if [ "$d" -eq 1 ]; then
        imgs=$((imgs + 1))
        if cmp -s "$Q/done/j$i/img.png" "$T/plain/ref/img.png" && grep -q '"image": "img.png"' "$Q/done/j$i/img.json" &&
            grep -q "\"job\": \"j$i\"" "$Q/done/j$i/img.json" && grep -q '"width": 64' "$Q/done/j$i/img.json"; then
            same=$((same + 1))
        fi
    fi
    i=$((i + 1))
done
echo "stress: $imgs done, $((jobs - imgs)) failed"
check "every job in done/ or failed/ exactly once ($once of $jobs, $both in both)" [ "$once" -eq "$jobs" ]
check "every done image is the plain render's and matches its sidecar ($same of $imgs)" [ "$same" -eq "$imgs" ]
temps=$(find "$Q" -name '.*' -type f | wc -l)
check "no temporary file anywhere ($temps)" [ "$temps" -eq 0 ]
if [ "$temps" -ne 0 ]; then find "$Q" -name '.*' -type f >&2; fi
finish
