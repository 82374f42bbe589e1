#!/bin/sh
# End to end: a suite (a compare job with `studies:`) of two tiny studies renders each into
# OUT/<suite>/<study>/ as if run alone with --out OUT/<suite> (references shared in
# OUT/<suite>/.cache/), then writes the suite's verdict.json, summary.csv (a leading study column),
# chart.svg and report.html; it resumes per study; bad suites exit 2 with file:line:col having
# written nothing; a failing study leaves nothing at the top; a queue takes a suite.
. tests/lib.sh
root=$(pwd)
mkdir -p "$T/jobs/studies"
study() { # study FILE NAME SAMPLER SAMPLER
    cat >"$T/jobs/studies/$1" <<EOF
name: $2
scenes: [$root/scenes/checker.yaml]
width: 16
height: 16
reference: { sampler: jitter, threshold: 10 }
seeds: [1, 2]
sweep: { threshold: [50, 25] }
variants:
  - { sampler: $3 }
  - { sampler: $4 }
EOF
}
study grid.yaml grid jitter uniform
study scatter.yaml scatter random poisson
printf '# two studies\nname: suite\nstudies: [studies/grid.yaml, studies/scatter.yaml]\n' >"$T/jobs/suite.yaml"

# 1. the run: every study's folder, the shared reference, the suite's own files
"$WORKER" --quiet --out "$T/out" "$T/jobs/suite.yaml" 2>"$T/run1.err"; rc=$?
check "suite exits 0 (got $rc: $(tail -n 1 "$T/run1.err"))" [ "$rc" -eq 0 ]
s=$T/out/suite
for st in grid scatter; do
    check "$st: 8 images in suite/$st/" [ "$(ls "$s/$st"/*.png 2>/dev/null | wc -l)" -eq 8 ]
    for f in summary.csv chart.svg report.html verdict.json; do
        check "$st: its own $f" test -s "$s/$st/$f"
    done
done
check "one reference for both studies (same scene, settings, size), in suite/.cache/" \
    [ "$(ls "$s"/.cache/ref-*[0-9a-f][0-9a-f].exr 2>/dev/null | wc -l)" -eq 1 ]
check "the second study reused the first's reference" grep -q "references: 1 rendered, 1 reused from cache" "$T/run1.err"
check "the summary line counts images and studies" grep -q "^suite: 16 images in 2 studies (grid 8, scatter 8)" "$T/run1.err"
check "the summary line ends with the verdict at equal CPU time" \
    grep -q -- "-> $T/out/suite/; at equal CPU time: grid: .*; scatter: " "$T/run1.err"
for f in verdict.json summary.csv chart.svg report.html; do
    check "suite: $f" test -s "$s/$f"
done
if command -v python3 >/dev/null 2>&1; then
    check "verdict.json parses, names the suite and both studies in order" python3 -c "
import json, sys
d = json.load(open(sys.argv[1]))
assert d['job'] == 'suite', d['job']
assert [x['study'] for x in d['studies']] == ['grid', 'scatter'], d['studies']
assert all(len(x['scenes']) == 1 for x in d['studies'])" "$s/verdict.json"
    check "chart.svg parses as XML" python3 -c "import sys, xml.etree.ElementTree as E; E.parse(sys.argv[1])" "$s/chart.svg"
else
    no "python3 is needed to parse verdict.json and chart.svg (ci/run installs it)"
fi
check "chart.svg: both studies' panels (2 studies x 2 panels x 2 variants = 8 lines)" \
    [ "$(grep -c '<polyline' "$s/chart.svg")" -eq 8 ]
csv=$s/summary.csv
check "summary.csv: a study column before the study's header" \
    [ "$(head -n 1 "$csv")" = "study,$(head -n 1 "$s/grid/summary.csv")" ]
check "summary.csv: 8 rows of each study" \
    [ "$(grep -c '^grid,checker,' "$csv")" -eq 8 -a "$(grep -c '^scatter,checker,' "$csv")" -eq 8 -a "$(wc -l <"$csv")" -eq 17 ]
check "summary.csv: a study's rows are its own summary.csv's" \
    [ "$(grep '^scatter,' "$csv" | cut -d, -f2-)" = "$(tail -n +2 "$s/scatter/summary.csv")" ]
html=$s/report.html
check "report: html5" sh -c "head -n 1 '$html' | grep -q '<!DOCTYPE html>'"
check "report: opens with the verdict, then the studies" \
    awk '/<h2/ { n++; if (n == 1 && !/Verdict/) exit 1; if (/id="study-grid"/) g = n; if (/id="study-scatter"/) s = n }
         END { exit !(g > 1 && s > g) }' "$html"
check "report: each study's chart inline" [ "$(grep -c '<svg xmlns' "$html")" -ge 2 ]
grep -o 'href="[^"]*"' "$html" | sed 's/^href="//; s/"$//' | sort -u >"$T/links"
check "report: links each study's own report" grep -qx 'grid/report.html' "$T/links"
unresolved=$(while read -r l; do [ -e "$s/$l" ] || echo "$l"; done <"$T/links")
check "report: every link resolves (unresolved: $unresolved)" [ -z "$unresolved" ]
check "report: nothing from the network" sh -c "! grep -Eqi '(src|href)=\"(https?:)?//|url\\(|@import' '$html'"

# 2. a study in the suite is the study run alone with --out OUT/<suite>: all current
"$WORKER" --quiet --out "$T/out/suite" "$T/jobs/studies/grid.yaml" 2>"$T/alone.err"
check "the study alone with --out OUT/suite finds its 8 images current" grep -q "^grid: 8 images .*8 of them current" "$T/alone.err"

# 3. resume per study; --force renders again
stamp() { ls -i "$s"/*/*.png | sort -k2; }
stamp >"$T/first"
"$WORKER" --quiet --out "$T/out" "$T/jobs/suite.yaml" 2>"$T/run2.err"; rc=$?
check "re-run exits 0 (got $rc)" [ "$rc" -eq 0 ]
check "re-run: all 16 current" grep -q "16 images in 2 studies (grid 8, scatter 8), 16 of them current" "$T/run2.err"
stamp >"$T/second"
check "re-run leaves every image untouched" cmp -s "$T/first" "$T/second"
check "re-run: both references reused" grep -q "references: 0 rendered, 2 reused from cache" "$T/run2.err"
"$WORKER" --quiet --force --out "$T/out" "$T/jobs/suite.yaml" 2>"$T/run3.err"
check "--force renders them all" sh -c "grep -q '^suite: 16 images' '$T/run3.err' && ! grep -q 'current' '$T/run3.err'"

# 4. progress on a terminal: a line as each study starts, then its images' lines
if command -v script >/dev/null 2>&1; then
    script -qec "'$WORKER' --out '$T/out' '$T/jobs/suite.yaml'" /dev/null >"$T/tty.out" 2>&1
    check "progress: a line per study" sh -c "grep -q '^study 1/2: grid' '$T/tty.out' && grep -q '^study 2/2: scatter' '$T/tty.out'"
    check "progress: the studies' image lines" [ "$(grep -c '^\[[ 0-9]*/8\] ' "$T/tty.out")" -eq 16 ]
else
    echo "note: script(1) missing, progress lines not checked"
fi

# 5. bad suites: exit 2, one line at file:line:col, nothing written
bad() { # bad NAME EXPECTED-TEXT: run $T/jobs/NAME.yaml (written before) and check the refusal
    "$WORKER" --quiet --out "$T/bad-out" "$T/jobs/$1.yaml" 2>"$T/$1.err"; rc=$?
    check "$1: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "$1: one line: $2 (got: $(cat "$T/$1.err"))" sh -c "[ \$(wc -l <'$T/$1.err') -eq 1 ] && grep -qF -- '$2' '$T/$1.err'"
    check "$1: nothing written" [ ! -e "$T/bad-out" ]
}
printf 'name: s\nstudies: [studies/grid.yaml]\nnmae: x\n' >"$T/jobs/unknown.yaml"
bad unknown "jobs/unknown.yaml:3:1: nmae: unknown key in suite (did you mean \"name\"?)"
printf 'name: s\nstudies: [studies/grid.yaml]\nwidth: 8\n' >"$T/jobs/jobkey.yaml"
bad jobkey "jobs/jobkey.yaml:3:1: width: not allowed in a suite"
sed 's/threshold: 10 }/threshold: 0 }/' "$T/jobs/studies/scatter.yaml" >"$T/jobs/studies/broken.yaml"
printf 'name: s\nstudies: [studies/grid.yaml, studies/broken.yaml]\n' >"$T/jobs/badstudy.yaml"
bad badstudy "jobs/studies/broken.yaml:5:42: threshold: must be a number in (0, 100]"
sed 's/^name: scatter/name: grid/' "$T/jobs/studies/scatter.yaml" >"$T/jobs/studies/grid2.yaml"
printf 'name: s\nstudies: [studies/grid.yaml, studies/grid2.yaml]\n' >"$T/jobs/twins.yaml"
bad twins 'jobs/twins.yaml:2:30: studies: '
check "twins: says both are named grid" grep -q 'both named "grid"' "$T/twins.err"
printf 'name: inner\nstudies: [grid.yaml]\n' >"$T/jobs/studies/nested.yaml"
printf 'name: s\nstudies: [studies/grid.yaml, studies/nested.yaml]\n' >"$T/jobs/nest.yaml"
bad nest "jobs/studies/nested.yaml:2:1: studies: a study cannot list studies itself"
printf 'name: s\nstudies: [studies/grid.yaml, studies/gone.yaml]\n' >"$T/jobs/missing.yaml"
bad missing "jobs/missing.yaml:2:30: studies: no study file at $T/jobs/studies/gone.yaml"
printf 'name: s\nstudies: []\n' >"$T/jobs/empty.yaml"
bad empty "jobs/empty.yaml:2:10: studies: must be a non-empty list of study files"
# a suite is a compare job: merge refuses it; --part I/N renders task I's share of its images
"$WORKER" merge --quiet --out "$T/bad-out" "$T/jobs/suite.yaml" 2>"$T/merge.err"; rc=$?
check "merge refuses a suite (exit $rc)" sh -c "[ $rc -eq 2 ] && grep -q 'a compare job renders whole images' '$T/merge.err'"
"$WORKER" --part 1/2 --quiet --out "$T/bad-out" "$T/jobs/suite.yaml" 2>"$T/part.err"; rc=$?
check "--part 1/2 of a suite renders its share (exit $rc): $(cat "$T/part.err")" sh -c "[ $rc -eq 0 ] && grep -q ': part 1/2: [0-9]* images rendered' '$T/part.err'"

# 6. a study that fails leaves nothing at the suite's top
mkdir -p "$T/out2/suite"
: >"$T/out2/suite/scatter" # the second study's folder is a file
"$WORKER" --quiet --out "$T/out2" "$T/jobs/suite.yaml" 2>"$T/fail.err"; rc=$?
check "a failing study fails the suite (got $rc)" [ "$rc" -ne 0 ]
check "the first study was rendered" [ "$(ls "$T"/out2/suite/grid/*.png 2>/dev/null | wc -l)" -eq 8 ]
check "nothing at the top" [ -z "$(ls "$T/out2/suite" | grep -v -e '^grid$' -e '^scatter$')" ]

# 7. a queue takes a suite: its studies resolve beside the queue's job file, outputs in done/<suite>/
q=$T/queue
mkdir -p "$q/studies"
cp "$T/jobs/studies/grid.yaml" "$T/jobs/studies/scatter.yaml" "$q/studies/"
cp "$T/jobs/suite.yaml" "$q/suite.yaml"
"$WORKER" --quiet --queue "$q" --once 2>"$T/queue.err"; rc=$?
check "queue: exit 0 (got $rc: $(tail -n 1 "$T/queue.err"))" [ "$rc" -eq 0 ]
check "queue: the suite filed in done/" [ -f "$q/done/suite.yaml" ]
check "queue: both studies and the suite's files in done/suite/" \
    [ "$(ls "$q"/done/suite/grid/*.png "$q"/done/suite/scatter/*.png | wc -l)" -eq 16 -a -s "$q/done/suite/verdict.json" ]
mv "$q/done/suite.yaml" "$q/suite.yaml"
"$WORKER" --quiet --queue "$q" --once 2>"$T/queue2.err"
check "queue: a re-queued suite resumes (16 current)" grep -q "16 of them current" "$T/queue2.err"
# worker status sums a finished suite's images, in its studies' folders, as a compare job's
"$WORKER" status "$q" --json >"$T/qs.json"
check "queue: status gives the done suite its 16 images' figures" python3 -c "
import json
d = [x for x in json.load(open('$T/qs.json'))['done'] if x['file'] == 'suite.yaml'][0]
assert d['images'] == 16 and d['cpu_s'] is not None and d['samples'] > 0, d
"
finish
