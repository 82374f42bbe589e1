#!/bin/sh
# e2e_compare_temps: the temporaries of a compare job's summary.csv, chart.svg and report.html left
# by a writer killed half-way (kill -9) are removed by the next run of that job; a live writer's
# (it holds the output folder's flock) are not touched: the next run waits for the lock.
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/.." && pwd)
printf 'name: cm\nscenes: [%s/scenes/checker.yaml]\nwidth: 8\nthreshold: 50\nvariants: [{ sampler: jitter }]\n' \
    "$root" >"$T/cm.yaml"
"$WORKER" --quiet --out "$T/out" "$T/cm.yaml" 2>/dev/null
check "first run: summary written" [ -s "$T/out/cm/summary.csv" ]
for f in summary.csv chart.svg report.html; do echo half >"$T/out/cm/.$f.tmp.AbC123"; done
"$WORKER" --quiet --out "$T/out" "$T/cm.yaml" 2>/dev/null; rc=$?
check "second run: exit 0 (got $rc)" [ "$rc" -eq 0 ]
for f in summary.csv chart.svg report.html; do
    check "a dead writer's .$f.tmp.AbC123 is removed" [ ! -e "$T/out/cm/.$f.tmp.AbC123" ]
done
# a live writer: holds the folder's lock while its temporary exists
echo live >"$T/out/cm/.summary.csv.tmp.LiVe12"
mkfifo "$T/release"
( flock 9; : >"$T/locked"; read -r _ <"$T/release" ) 9<"$T/out/cm" & lpid=$!
for _ in $(seq 1 200); do [ -f "$T/locked" ] && break; sleep 0.05; done
"$WORKER" --quiet --out "$T/out" "$T/cm.yaml" 2>/dev/null & wpid=$!
sleep 1 # the run reaches the lock and waits there
check "a live writer's temporary is left while it holds the lock" [ -e "$T/out/cm/.summary.csv.tmp.LiVe12" ]
check "the run waits for the lock" kill -0 "$wpid"
rm -f "$T/out/cm/.summary.csv.tmp.LiVe12" # the live writer renames or removes its own
echo >"$T/release"; wait "$lpid"
wait "$wpid"; rc=$?
check "the run ends once the lock comes (got $rc)" [ "$rc" -eq 0 ]
check "no temporaries left" [ -z "$(ls -A "$T/out/cm" | grep '^\.')" ]
finish
