#!/bin/sh
# A compare job in a queue is spread over the workers (issue 31): a study of 60 renders (2 scenes x
# 3 variants x 2 thresholds x 5 seeds) and 2 references (4 entries: each reference's two halves), drained by 3 local workers killed with
# kill -9 at random (and replaced), gives images byte-identical to a one-process run and the same
# verdict at equal samples and for the slopes; every render is filed exactly once, and the gather
# runs exactly once.
. tests/lib.sh
root=$(pwd)
rnd() { od -An -N2 -tu2 /dev/urandom | tr -d ' '; } # 0..65535
. tests/lib_study.sh
study() { small_study spread "$root" "1, 2, 3, 4, 5" "jitter random uniform"; }
study >"$T/spread.yaml"
"$WORKER" --quiet --out "$T/plain" "$T/spread.yaml" 2>"$T/plain.log"
check "the one-process run: $(cat "$T/plain.log")" [ -s "$T/plain/spread/verdict.json" ]

Q=$T/q; mkdir -p "$Q"
study >"$Q/spread.yaml"
start() { "$WORKER" --queue "$Q" --once --quiet --lease-timeout 2 --poll 0.1 >/dev/null 2>>"$T/workers.log" & echo $!; }
pids="$(start) $(start) $(start)"
kills=0; rounds=0
while [ ! -f "$Q/done/spread.yaml" ] && [ "$rounds" -lt 600 ]; do
    rounds=$((rounds + 1))
    sleep 0.$(($(rnd) % 3 + 1))
    set -- $pids
    victim=$(eval echo "\${$(($(rnd) % $# + 1))}")
    [ "$kills" -lt 12 ] && kill -9 "$victim" 2>/dev/null && kills=$((kills + 1))
    alive=""
    for p in $pids; do
        if kill -0 "$p" 2>/dev/null; then alive="$alive $p"; elif [ ! -f "$Q/done/spread.yaml" ]; then alive="$alive $(start)"; fi
    done
    pids=$alive
done
for p in $pids; do while kill -0 "$p" 2>/dev/null; do sleep 0.1; done; done
echo "study: $kills kills"
check "the study was gathered ($kills workers killed): $(tail -n 3 "$T/workers.log")" [ -f "$Q/done/spread.yaml" ]
S=$Q/spread/spread
check "every render filed in the study's done/ exactly once: 64 (each reference two halves) + the gather" [ "$(ls "$S/done" | grep -c 'yaml$')" -eq 65 ]
check "none failed, none waiting or running" [ -z "$(ls "$S/failed" "$S/running" "$S" | grep 'yaml')" ]
check "the gather ran exactly once" [ "$(grep -c 'c-gather.yaml: gathered into' "$T/workers.log")" -eq 1 ]
check "done/spread/ holds the same files as the one-process run" \
    [ "$(cd "$T/plain/spread" && ls)" = "$(cd "$Q/done/spread" && ls)" ]
same=0
for f in "$T"/plain/spread/*.png "$T"/plain/spread/*.exr; do
    cmp -s "$f" "$Q/done/spread/$(basename "$f")" && same=$((same + 1))
done
check "all 120 images byte-identical to the one-process run ($same)" [ "$same" -eq 120 ]
check "its references are the one-process run's bytes" \
    sh -c "for f in '$T'/plain/.cache/*.exr; do cmp -s \"\$f\" '$Q'/done/.cache/\$(basename \"\$f\") || exit 1; done"
rankings() { # rankings FILE: each scene's equal-samples and slope rankings
    python3 -c 'import json,sys
v=json.load(open(sys.argv[1]))
for st in v["studies"]:
    for sc in st["scenes"]:
        for k in ("equal_samples", "slopes"):
            r=sc[k]
            print(sc.get("scene"), k, r["status"], [(x["variant"], x["rank"]) for x in r["ranking"]])' "$1"
}
check "the same verdict at equal samples and for the slopes" \
    [ "$(rankings "$T/plain/spread/verdict.json")" = "$(rankings "$Q/done/spread/verdict.json")" ]
"$WORKER" status "$Q" >"$T/status-done.txt" 2>&1
check "status: the done study shows its 60 images' figures summed: $(grep spread "$T/status-done.txt")" \
    grep -q '^  spread.yaml  finished .*  60 images  wall (sum) ' "$T/status-done.txt"
check "sidecars record host and CPU model" grep -q '"cpu_model": "..*"' "$Q/done/spread/checker-jitter-t50-s1.json"
check "one CPU model: equal CPU time not marked" [ -z "$(grep mixes_machines "$Q/done/spread/verdict.json")" ]
# images of another CPU model (their sidecars say so): the equal-CPU-time ranking is marked as
# mixing machines in verdict.json and the report; the equal-samples and slope rankings are unchanged
for f in "$T"/plain/spread/*-s1.json; do sed -i 's/"cpu_model": "[^"]*"/"cpu_model": "Other CPU 9000"/' "$f"; done
"$WORKER" --quiet --out "$T/plain" "$T/spread.yaml" 2>"$T/mixed.log"
check "mixed CPU models: verdict.json marks equal CPU time" grep -q '"equal_cpu_time_mixes_machines": true' "$T/plain/spread/verdict.json"
check "... and names the models" grep -q '"cpu_models": ".*Other CPU 9000' "$T/plain/spread/verdict.json"
check "... the report says so, and whose figures equal CPU time uses" grep -q 'rendered on 2 CPU models: their own CPU seconds (summary.csv) do not compare; equal CPU time is ranked by the cost design' "$T/plain/spread/report.html"
check "... equal samples and slopes unchanged" \
    [ "$(rankings "$T/plain/spread/verdict.json")" = "$(rankings "$Q/done/spread/verdict.json")" ]
check "no temporary, lease or lock file left: $(find "$Q" -name ".*tmp*" -o -name "*.lease" -o -name "*.lock")" [ -z "$(find "$Q" -name '.*tmp*' -o -name '*.lease' -o -name '*.lock')" ]

# worker status on a study in progress shows it as one line: renders done/total, failed, ETA
Q2=$T/q2; mkdir -p "$Q2"
study >"$Q2/spread.yaml"
"$WORKER" --queue "$Q2" --once --quiet >/dev/null 2>"$T/w2.log" & w=$!
for _ in $(seq 1 200); do [ -n "$(ls "$Q2/spread/spread/done" 2>/dev/null | grep b-img)" ] && break; sleep 0.05; done
kill -STOP "$w"
"$WORKER" status "$Q2" >"$T/status.txt" 2>&1
"$WORKER" status "$Q2" --json >"$T/status.json" 2>&1
kill -CONT "$w"; wait "$w"
check "status: one study line: $(cat "$T/status.txt")" grep -Eq '^  spread.yaml  study spread  [0-9]+/64 renders done, 0 failed' "$T/status.txt"
check "status --json: the study's progress" python3 -c 'import json,sys
s=json.load(open(sys.argv[1]))["studies"][0]
assert s["file"] == "spread.yaml" and s["renders"] == 64 and 0 < s["done"] < 64 and s["failed"] == 0, s' "$T/status.json"

# SIGTERM (a Slurm pre-emption) while a study's render runs: that render goes back to the study's
# waiting entries, and the worker exits 0
Q4=$T/q4; mkdir -p "$Q4"
printf 'name: slow\nscenes: [%s/scenes/cornell.yaml]\nwidth: 32\nprocesses: 1\nvariants: [{ sampler: jitter, threshold: 2 }]\n' "$root" >"$Q4/slow.yaml"
"$WORKER" --queue "$Q4" --once --quiet >/dev/null 2>"$T/w6.log" & w=$!
child=$(render_child "$w")
kill -TERM "$w"; wait "$w"; rc=$?
check "SIGTERM: exit 0 (got $rc): $(cat "$T/w6.log")" [ "$rc" -eq 0 ]
check "... the render is waiting again in the study" eval '[ -f "$Q4/spread/slow/b-img-0-00000.yaml" ] && [ -z "$(ls "$Q4/spread/slow/running")" ]'

# a render that fails (its render process killed, no retries) leaves the study waiting: status
# counts it, `requeue DIR X` puts the study's failed renders back, and the study then completes
Q3=$T/q3; mkdir -p "$Q3"
printf 'name: slow\nscenes: [%s/scenes/cornell.yaml]\nwidth: 32\nprocesses: 1\nseeds: [1, 2]\nvariants: [{ sampler: jitter, threshold: 2 }]\n' "$root" >"$Q3/slow.yaml"
"$WORKER" --queue "$Q3" --once --quiet --retries 0 >/dev/null 2>"$T/w3.log" & w=$!
child=$(render_child "$w")
kill -9 "$child"
wait "$w"; rc=$?
check "a study with a failed render: the worker exits 1 (got $rc)" [ "$rc" -eq 1 ]
check "... the study waits, not gathered" eval '[ ! -f "$Q3/done/slow.yaml" ] && [ -f "$Q3/spread/slow/job/slow.yaml" ]'
"$WORKER" status "$Q3" >"$T/status3.txt" 2>&1
check "status: 1/2 done, 1 failed: $(cat "$T/status3.txt")" grep -q 'slow.yaml  study slow  1/2 renders done, 1 failed' "$T/status3.txt"
check "status: no ETA, it waits for a requeue of its failed render" \
    grep -q 'slow.yaml  study slow  1/2 renders done, 1 failed, .*ETA -- (waits for its failed renders to be requeued' "$T/status3.txt"
"$WORKER" status "$Q3" --json >"$T/status3.json" 2>&1
check "status --json: its eta_s null" python3 -c 'import json,sys
s=json.load(open(sys.argv[1]))["studies"][0]
assert s["eta_s"] is None and s["waits_for_requeue"] is True, s' "$T/status3.json"
"$WORKER" requeue "$Q3" slow >"$T/rq.txt" 2>&1; rc=$?
check "requeue of the study: exit 0 (got $rc), its failed render put back: $(cat "$T/rq.txt")" grep -q '1 failed render of the study requeued' "$T/rq.txt"
check "... its log removed too" [ -z "$(ls "$Q3/spread/slow/failed")" ]
"$WORKER" --queue "$Q3" --once --quiet >/dev/null 2>"$T/w4.log"; rc=$?
check "the study then completes (exit $rc)" eval '[ "$rc" -eq 0 ] && [ -f "$Q3/done/slow.yaml" ] && [ -s "$Q3/done/slow/summary.csv" ]'
"$WORKER" --queue "$Q3" --once >/dev/null 2>"$T/w5.log"
check "a --once worker on an empty queue says so in one line: $(cat "$T/w5.log")" \
    eval '[ "$(grep -c "no job waiting, nothing to do" "$T/w5.log")" -eq 1 ] && [ "$(grep -c . "$T/w5.log")" -eq 1 ]'
finish
