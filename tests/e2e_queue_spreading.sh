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
    lease_text "$3" >"$1/running/$2.lease"
}
# begin N: queue Q=$T/qN holding the study claimed by a live process of ours ($holder); a --once
# worker ($w, its log $log) started on it; waited=0 once it says it waits for the spread (up to 20 s),
# 1 when it exits first
begin() {
    Q=$T/q$1; log=$T/w$1.log; mkdir -p "$Q"
    study >"$Q/sp.yaml"
    sleep 600 & holder=$!
    claim "$Q" sp.yaml "$holder"
    "$WORKER" --queue "$Q" --once --lease-timeout 30 --poll 0.1 >/dev/null 2>"$log" & w=$!
    waited=1
    for _ in $(seq 1 400); do
        grep -q 'waiting for it to be spread' "$log" 2>/dev/null && { waited=0; break; }
        kill -0 "$w" 2>/dev/null || break
        sleep 0.05
    done
}
# end: the worker's exit status into rc (killed after 30 s); gathered=0 when it exited 0 and the
# study was gathered
end() {
    for _ in $(seq 1 600); do kill -0 "$w" 2>/dev/null || break; sleep 0.05; done
    kill "$w" 2>/dev/null; wait "$w"; rc=$?
    gathered=1
    [ "$rc" -eq 0 ] && [ -f "$Q/done/sp.yaml" ] && [ -s "$Q/done/sp/verdict.json" ] && gathered=0
}

# 1. the claimer lives and spreads the study: the waiting worker renders both images and gathers
begin 1
check "a --once worker waits while a live worker spreads a compare job: $(cat "$log")" [ "$waited" -eq 0 ]
S=$Q/spread/.sp.new.$holder
mkdir -p "$S/job" "$S/running" "$S/done" "$S/failed"
cp "$Q/running/sp.yaml" "$S/study.job"
# study.key: the record of what was written (the job's FNV-1a hash, the entries' names)
python3 -c 'import sys
h = 0xcbf29ce484222325
for b in open(sys.argv[1], "rb").read():
    h = ((h ^ b) * 0x100000001b3) % (1 << 64)
print("worker study key 1\njob %016x" % h)' "$S/study.job" >"$S/study.key"
for e in b-img-0-00000 b-img-0-00001 c-gather; do echo "# $e" >"$S/$e.yaml"; echo "entry $e.yaml" >>"$S/study.key"; done
mv "$S" "$Q/spread/sp"
rm "$Q/running/sp.yaml.lease"
mv "$Q/running/sp.yaml" "$Q/spread/sp/job/sp.yaml"
kill "$holder"
end
check "... then renders the study's images and gathers it (exit $rc): $(tail -n 2 "$log")" [ "$gathered" -eq 0 ]
check "... both images rendered by it" [ "$(grep -c 'sp/b-img-0-0000[01].yaml: sp: image' "$log")" -eq 2 ]
check "... said once that it waits" [ "$(grep -c 'waiting for it to be spread' "$log")" -eq 1 ]

# 2. the claimer dies before it has spread the study: the waiting worker recovers the claim and
# spreads and drains the study itself
begin 2
check "a --once worker waits for a claimed compare job: $(cat "$log")" [ "$waited" -eq 0 ]
kill "$holder"; wait "$holder" 2>/dev/null
end
check "... its claimer dead, it takes the job back, spreads and gathers it (exit $rc): $(tail -n 2 "$log")" \
    [ "$gathered" -eq 0 ]
check "... after returning the dead claim to the queue" grep -q 'sp.yaml: returned to the queue: its worker' "$log"

# 3. a plain job running elsewhere: nothing a --once worker could help with, it exits at once
Q=$T/q3; mkdir -p "$Q"
printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nheight: 6\n' "$root" >"$Q/plain.yaml"
sleep 600 & holder=$!
claim "$Q" plain.yaml "$holder"
timeout 20 "$WORKER" --queue "$Q" --once --lease-timeout 30 --poll 0.1 >/dev/null 2>"$T/w3.log"; rc=$?
kill "$holder"
check "a plain job running elsewhere: a --once worker exits 0 at once (got $rc): $(cat "$T/w3.log")" [ "$rc" -eq 0 ]
check "... saying it had nothing to do" grep -q 'no job waiting, nothing to do' "$T/w3.log"

# 4. the compare job claimed this instant, its lease not yet written (the claimer renames first):
# the waiting worker names its holder once the lease is there, never "pid 0 on ?"
Q=$T/q4; mkdir -p "$Q/running"; study >"$Q/running/sp.yaml"
sleep 600 & holder=$!
"$WORKER" --queue "$Q" --once --lease-timeout 30 --poll 0.1 >/dev/null 2>"$T/w4.log" & w=$!
sleep 0.2
lease_text "$holder" >"$Q/running/sp.yaml.lease.tmp"; mv "$Q/running/sp.yaml.lease.tmp" "$Q/running/sp.yaml.lease"
for _ in $(seq 1 200); do grep -q 'waiting for it to be spread' "$T/w4.log" && break; sleep 0.05; done
kill "$w" "$holder"; wait "$w" 2>/dev/null
check "a claim whose lease comes a moment later: its holder named: $(cat "$T/w4.log")" \
    grep -q "sp.yaml: a compare job claimed by pid $holder on $(hostname): waiting for it to be spread" "$T/w4.log"
check "... never an unknown holder" sh -c "! grep -q 'pid 0 on' '$T/w4.log'"
finish
