#!/bin/sh
# A compare job in a queue directory: rendered into done/<name>/ (its relative scene path still
# resolving from the queue directory), the job file filed in done/; a bad one goes to failed/.
. tests/lib.sh
q=$T/queue
mkdir -p "$q" "$T/scenes"
cp scenes/checker.yaml "$T/scenes/checker.yaml"
cat >"$q/study.yaml" <<YAML
name: study
scenes: [../scenes/checker.yaml]
width: 12
reference: { sampler: jitter, threshold: 25 }
seeds: [1, 2]
sweep: { threshold: [50, 34] }
variants:
  - { sampler: jitter }
  - { sampler: random }
YAML
printf 'name: broken\nscenes: [../scenes/checker.yaml]\nsweep: { threshold: [] }\nvariants:\n  - { sampler: jitter }\n' >"$q/broken.yaml"
"$WORKER" --quiet --queue "$q" --once 2>"$T/err"; rc=$?
check "queue with a bad compare job exits 2 (got $rc)" [ "$rc" -eq 2 ]
check "compare job filed in done/" [ -f "$q/done/study.yaml" ]
check "its 8 images in done/study/" [ "$(ls "$q"/done/study/*.png 2>/dev/null | wc -l)" -eq 8 ]
check "its summary.csv, chart.svg and report.html" eval '[ -s "$q/done/study/summary.csv" ] && [ -s "$q/done/study/chart.svg" ] && [ -s "$q/done/study/report.html" ]'
check "bad compare job filed in failed/" [ -f "$q/failed/broken.yaml" ]
check "its log names file:line:col" grep -q 'broken.yaml:3:[0-9]*: ' "$q/failed/broken.log"
check "nothing left running" [ -z "$(ls "$q/running" 2>/dev/null | grep yaml)" ]
mv "$q/done/study.yaml" "$q/study.yaml"
"$WORKER" --quiet --queue "$q" --once 2>"$T/err2"
check "requeued compare job resumes: all 8 current" grep -q "8 of them current" "$T/err2"
# a compare job that loads but fails (its output folder is a file) logs under its name:
# failed/<name>.log, as SPEC says; only a job file that does not load logs under the file's stem
q2=$T/queue2
mkdir -p "$q2/done"
printf 'name: renamed\nscenes: [../scenes/checker.yaml]\nwidth: 8\nheight: 6\nvariants:\n  - { sampler: jitter, threshold: 50 }\n' >"$q2/cj.yaml"
: >"$q2/done/renamed"
"$WORKER" --quiet --queue "$q2" --once 2>"$T/err3"; rc=$?
check "a compare job whose folder is a file fails (got $rc)" [ "$rc" -ne 0 ]
check "its job file in failed/" [ -f "$q2/failed/cj.yaml" ]
check "its log is failed/<name>.log" grep -q "a file is in the way" "$q2/failed/renamed.log"

finish
