#!/bin/sh
# A --once worker that finds nothing waiting while a compare job it could help with is being spread
# (claimed into running/ by a live worker, its spread/ folder not yet made) waits for the spread and
# drains it, instead of saying "nothing to do" and leaving the study to the one worker that claimed
# it. Made deterministic by standing in for that worker: the claim is placed in running/ with a
# lease naming a live process of ours, then the spread appears (as queue_study.c makes it), or that
# process dies (the claim is recovered, and the waiting worker spreads the study itself). A plain job
# running elsewhere does not hold a --once worker back.
. tests/lib.sh
root=$(pwd)
study() {
    printf 'name: sp\nscenes: [%s/scenes/checker.yaml]\nwidth: 8\nheight: 6\nprocesses: 1\n' "$root"
    printf 'seeds: [1, 2]\nvariants: [{ sampler: jitter, threshold: 50 }]\n'
}
# claim Q NAME PID: NAME (written to Q/NAME first) claimed into Q/running/ by process PID of this host
claim() {
    mkdir -p "$1/running"
    mv "$1/$2" "$1/running/$2"
    printf 'host %s\npid %s\nstart %s\ntoken test:%s\n' "$(hostname)" "$3" "$(date +%s)" "$3" >"$1/running/$2.lease"
}
# waits Q LOG PID: wait (up to 20 s) until worker PID says it waits for the spread, or has exited
waits() {
    for _ in $(seq 1 400); do
        grep -q 'waiting for it to be spread' "$2" 2>/dev/null && return 0
        kill -0 "$3" 2>/dev/null || return 1
        sleep 0.05
    done
    return 1
}
# gathered RC Q: the worker exited 0 and the study sp of queue Q was gathered
gathered() { [ "$1" -eq 0 ] && [ -f "$2/done/sp.yaml" ] && [ -s "$2/done/sp/verdict.json" ]; }

# 1. the claimer lives and spreads the study: the waiting worker renders both images and gathers
Q=$T/q1; mkdir -p "$Q"
study >"$Q/sp.yaml"
sleep 600 & holder=$!
claim "$Q" sp.yaml "$holder"
"$WORKER" --queue "$Q" --once --lease-timeout 30 --poll 0.1 >/dev/null 2>"$T/w1.log" & w=$!
waits "$Q" "$T/w1.log" "$w"; waited=$?
check "a --once worker waits while a live worker spreads a compare job: $(cat "$T/w1.log")" [ "$waited" -eq 0 ]
S=$Q/spread/.sp.new.$holder
mkdir -p "$S/job" "$S/running" "$S/done" "$S/failed"
cp "$Q/running/sp.yaml" "$S/study.job"
for e in b-img-0-00000 b-img-0-00001 c-gather; do echo "# $e" >"$S/$e.yaml"; done
mv "$S" "$Q/spread/sp"
rm "$Q/running/sp.yaml.lease"
mv "$Q/running/sp.yaml" "$Q/spread/sp/job/sp.yaml"
kill "$holder"
for _ in $(seq 1 600); do kill -0 "$w" 2>/dev/null || break; sleep 0.05; done
kill "$w" 2>/dev/null; wait "$w"; rc=$?
check "... then renders the study's images and gathers it (exit $rc): $(tail -n 2 "$T/w1.log")" \
    gathered "$rc" "$Q"
check "... both images rendered by it" [ "$(grep -c 'sp/b-img-0-0000[01].yaml: sp: image' "$T/w1.log")" -eq 2 ]
check "... said once that it waits" [ "$(grep -c 'waiting for it to be spread' "$T/w1.log")" -eq 1 ]

# 2. the claimer dies before it has spread the study: the waiting worker recovers the claim and
# spreads and drains the study itself
Q=$T/q2; mkdir -p "$Q"
study >"$Q/sp.yaml"
sleep 600 & holder=$!
claim "$Q" sp.yaml "$holder"
"$WORKER" --queue "$Q" --once --lease-timeout 30 --poll 0.1 >/dev/null 2>"$T/w2.log" & w=$!
waits "$Q" "$T/w2.log" "$w"; waited=$?
check "a --once worker waits for a claimed compare job: $(cat "$T/w2.log")" [ "$waited" -eq 0 ]
kill "$holder"; wait "$holder" 2>/dev/null
for _ in $(seq 1 600); do kill -0 "$w" 2>/dev/null || break; sleep 0.05; done
kill "$w" 2>/dev/null; wait "$w"; rc=$?
check "... its claimer dead, it takes the job back, spreads and gathers it (exit $rc): $(tail -n 2 "$T/w2.log")" \
    gathered "$rc" "$Q"
check "... after returning the dead claim to the queue" grep -q 'sp.yaml: returned to the queue: its worker' "$T/w2.log"

# 3. a plain job running elsewhere: nothing a --once worker could help with, it exits at once
Q=$T/q3; mkdir -p "$Q"
printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nheight: 6\n' "$root" >"$Q/plain.yaml"
sleep 600 & holder=$!
claim "$Q" plain.yaml "$holder"
timeout 20 "$WORKER" --queue "$Q" --once --lease-timeout 30 --poll 0.1 >/dev/null 2>"$T/w3.log"; rc=$?
kill "$holder"
check "a plain job running elsewhere: a --once worker exits 0 at once (got $rc): $(cat "$T/w3.log")" [ "$rc" -eq 0 ]
check "... saying it had nothing to do" grep -q 'no job waiting, nothing to do' "$T/w3.log"
finish
