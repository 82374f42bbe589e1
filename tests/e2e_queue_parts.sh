#!/bin/sh
# e2e_queue_parts: a study spread over a queue is cut into entries by its estimated cost (issue 40):
# the seed's experiment (jobs/seed-experiment.yaml: one reference, three images) scaled down, with
# entry_cpu_s: small enough that every render is cut into row parts, drained by three --once
# workers: at least 12 entries, each part rendered once, each render merged once, the gather once,
# every image byte-identical to a one-process run (sidecars equal apart from times, host and the
# split); then the same under kill -9 at random moments. SIZE and TARGET (default 20 and 0.15)
# scale it: SIZE=60 TARGET=2 is BENCH.md's measured run.
. tests/lib.sh
root=$(pwd)
SIZE=${SIZE:-20}
TARGET=${TARGET:-0.15}
rnd() { od -An -N2 -tu2 /dev/urandom | tr -d ' '; } # 0..65535
seed_job() {
    sed -e "s|^scenes: \[checker\]|scenes: [$root/scenes/checker.yaml]|" -e "s/^width: 600/width: $SIZE/" \
        -e "s/^height: 600/height: $SIZE\nentry_cpu_s: $TARGET/" "$root/jobs/seed-experiment.yaml"
}
seed_job >"$T/seed.yaml"
"$WORKER" --quiet --out "$T/plain" "$T/seed.yaml" 2>"$T/plain.log"
check "the one-process run: $(cat "$T/plain.log")" [ -s "$T/plain/seed-experiment/verdict.json" ]
# the sidecar without what differs between two runs of one study on one machine in other folders and
# another split: times, host, the split (processes, parts, per_process) and the paths (job file, reference)
strip() {
    python3 -c 'import json,sys
d=json.load(open(sys.argv[1]))
def clean(o):
    if isinstance(o, dict):
        return {k: clean(v) for k, v in o.items() if not (k.endswith("_s") or k in ("host", "per_process", "processes", "parts", "peak_rss_kb", "sampler_s", "sampling_share", "ns_per_sample", "job_file", "reference"))}
    return o
print(json.dumps(clean(d), sort_keys=True))' "$1"
}
drain() { # drain Q KILLS: three --once workers on Q (up to KILLS of them killed with -9 and replaced)
    kills=0; rounds=0
    start() { "$WORKER" --queue "$1" --once --quiet --lease-timeout 2 --poll 0.1 >/dev/null 2>>"$1.log" & echo $!; }
    pids="$(start "$1") $(start "$1") $(start "$1")"
    while [ ! -f "$1/done/seed.yaml" ] && [ "$rounds" -lt 1200 ]; do
        rounds=$((rounds + 1))
        sleep 0.$(($(rnd) % 3 + 1))
        set -- "$1" "$2" $pids
        victim=$(eval echo "\${$(($(rnd) % ($# - 2) + 3))}")
        [ "$kills" -lt "$2" ] && kill -9 "$victim" 2>/dev/null && kills=$((kills + 1))
        alive=""
        for p in $pids; do
            if kill -0 "$p" 2>/dev/null; then alive="$alive $p"; elif [ ! -f "$1/done/seed.yaml" ]; then alive="$alive $(start "$1")"; fi
        done
        pids=$alive
    done
    for p in $pids; do while kill -0 "$p" 2>/dev/null; do sleep 0.1; done; done
}
verify() { # verify Q WHAT
    Q=$1; S=$Q/spread/seed; O=$Q/done/seed-experiment
    check "$2: the study was gathered: $(tail -n 3 "$Q.log")" [ -f "$Q/done/seed.yaml" ]
    n=$(ls "$S/done" | grep -c '^[ab]-.*yaml$')
    check "$2: at least 12 entries ($n), renders cut into row parts" eval '[ "$n" -ge 12 ] && ls "$S/done" | grep -q "^b-img-0-0000[0-2]-p0-[0-9]*.yaml$" && ls "$S/done" | grep -q "^a-ref-0-0-1-p0-"'
    check "$2: none failed, none waiting or running" [ -z "$(ls "$S/failed" "$S/running" "$S" | grep 'yaml')" ]
    check "$2: the gather ran once" [ "$(grep -c 'c-gather.yaml: gathered into' "$Q.log")" -eq 1 ]
    check "$2: the same files as the one-process run (no part left)" \
        [ "$(cd "$T/plain/seed-experiment" && ls -A)" = "$(cd "$O" && ls -A)" ]
    check "$2: the same cache files (no part left)" [ "$(cd "$T/plain/.cache" && ls -A)" = "$(cd "$Q/done/.cache" && ls -A)" ]
    same=0
    for f in "$T"/plain/seed-experiment/*.png "$T"/plain/seed-experiment/*.exr "$T"/plain/.cache/*.exr; do
        case $f in */.cache/*) g=$Q/done/.cache/$(basename "$f") ;; *) g=$O/$(basename "$f") ;; esac
        cmp -s "$f" "$g" && same=$((same + 1))
    done
    check "$2: all 6 images and 3 reference files byte-identical to the one-process run ($same)" [ "$same" -eq 9 ]
    sc=0
    for f in "$T"/plain/seed-experiment/*.json; do
        case $f in */verdict.json) continue ;; esac
        [ "$(strip "$f")" = "$(strip "$O/$(basename "$f")")" ] && sc=$((sc + 1))
    done
    check "$2: the 3 sidecars equal apart from times, host and the split ($sc)" [ "$sc" -eq 3 ]
}
# status mid-study: one worker stopped while it holds a lease, after an entry is done
Q=$T/q0; mkdir -p "$Q"; cp "$T/seed.yaml" "$Q/seed.yaml"
"$WORKER" --queue "$Q" --once --quiet --poll 0.1 >/dev/null 2>>"$Q.log" & w=$!
n=0; while [ "$n" -lt 600 ] && ! ls "$Q/spread/seed/done" 2>/dev/null | grep -q yaml; do sleep 0.05; n=$((n + 1)); done
kill -STOP "$w"
n=0; while [ "$n" -lt 600 ] && ! ls "$Q/spread/seed/running" | grep -q 'lease$'; do kill -CONT "$w"; sleep 0.02; kill -STOP "$w"; n=$((n + 1)); done
"$WORKER" status "$Q" --json >"$T/status.json" 2>&1
"$WORKER" status "$Q" >"$T/status.txt" 2>&1
kill -9 "$w"; kill -CONT "$w"; wait "$w" 2>/dev/null
check "status: a spread study's CPU done and left by its plan, its finish on the one worker holding a lease: $(cat "$T/status.txt")" \
    python3 -c 'import json,sys
s=json.load(open(sys.argv[1]))["studies"][0]
t=sum(float(l.split()[0]) for l in open(sys.argv[2]))
assert s["cpu_done_s"] > 0 and s["cpu_left_s"] > 0 and abs(s["cpu_done_s"] + s["cpu_left_s"] - t) < 1e-3 * t, (s, t)
assert s["lease_workers"] == 1 and s["finish_s"] > 0, s' "$T/status.json" "$Q/spread/seed/plan.txt"
check "status: its text says so" grep -Eq '^    CPU about [0-9]+ s done, [0-9]+ s left \(estimated by the plan\); predicted finish in about [0-9]+ s on the 1 worker holding leases now$' "$T/status.txt"
Q=$T/q1; mkdir -p "$Q"; cp "$T/seed.yaml" "$Q/seed.yaml"
drain "$Q" 0
verify "$Q" "three workers"
names=$(ls "$Q/spread/seed/done" | grep '^[ab]-.*-p[0-9].*yaml$' | sed 's/.yaml$//')
once=1
for e in $names; do [ "$(grep -c "/$e.yaml: .*: rendered" "$Q.log")" -eq 1 ] || once=0; done
check "three workers: each part rendered once" [ "$once" -eq 1 ]
merges=$(grep -c 'merged into its image and sidecar' "$Q.log")
renders=$(ls "$Q/spread/seed/done" | grep -- '-p0-' | wc -l)
check "three workers: each cut render merged once ($merges merges, $renders renders cut)" [ "$merges" -eq "$renders" ]
# queued again, as it is: nothing rendered (every entry finds its render merged, every image current)
mv "$Q/done/seed.yaml" "$Q/seed.yaml" && rm -rf "$Q/spread/seed"
: >"$Q.log"; drain "$Q" 0
check "queued again: nothing rendered ($(grep -c ': rendered' "$Q.log") renders)" eval '[ -f "$Q/done/seed.yaml" ] && grep -q "merged already" "$Q.log" && ! grep -q ": rendered" "$Q.log"'
Q=$T/q2; mkdir -p "$Q"; cp "$T/seed.yaml" "$Q/seed.yaml"
drain "$Q" 8
echo "kill test: $kills kills"
verify "$Q" "under kill -9 ($kills kills)"
finish
