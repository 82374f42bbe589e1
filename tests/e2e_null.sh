#!/bin/sh
# A YAML null (nothing, ~, null) on an optional key means its default, in job files, compare jobs
# and scenes; on a required key it is a one-line "needs a value" error at its file:line:col, exit 2.
. tests/lib.sh
S=$(pwd)/scenes/checker.yaml
# optional keys given null render like the job without them
for kv in 'name: ~' 'seed: null' 'reference:' 'output: ~' 'light_sampler: Null' 'processes: NULL' \
    'priority:' 'light_threshold: ~' 'format: ~'; do
    printf 'scene: %s\nwidth: 8\nthreshold: 20\n%s\n' "$S" "$kv" >"$T/j.yaml"
    rm -rf "$T/out"
    "$WORKER" --quiet --out "$T/out" "$T/j.yaml" 2>"$T/err"; rc=$?
    check "job '$kv': rendered with the default (rc $rc: $(head -n 1 "$T/err"))" [ "$rc" -eq 0 ]
    check "job '$kv': image under the default name" [ -s "$T/out/j/j.png" ]
done
# a quoted "~" is a string, not a null
printf 'scene: %s\nwidth: 8\nname: "~"\n' "$S" >"$T/j.yaml"
"$WORKER" --quiet --out "$T/out" "$T/j.yaml" 2>/dev/null
check 'name: "~" is a string (an invalid name)' [ $? -eq 2 ]
# a typo given null is still an unknown key
printf 'scene: %s\nwidth: 8\nnmae: ~\n' "$S" >"$T/j.yaml"
"$WORKER" --quiet --out "$T/out" "$T/j.yaml" 2>"$T/err"
check "nmae: ~ is an unknown key" grep -q 'unknown key' "$T/err"
# required keys given null: "needs a value" at the value, exit 2, nothing written
need() { # need FILE LINE:COL KEY [RUN]: run RUN (default FILE); the error is at FILE:LINE:COL
    rm -rf "$T/out"
    "$WORKER" --quiet --out "$T/out" "${4:-$1}" 2>"$T/err"; rc=$?
    check "$3 null: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "$3 null: '$1:$2: $3: needs a value', got: $(cat "$T/err")" grep -q "^$1:$2: $3: needs a value" "$T/err"
    check "$3 null: one line" [ "$(grep -c . "$T/err")" -eq 1 ]
    check "$3 null: nothing written" [ ! -e "$T/out" ]
}
printf 'width: 8\nscene: ~\n' >"$T/j.yaml"
need "$T/j.yaml" 2:8 scene
# compare jobs: optional keys null take their defaults; scenes and variants are required
printf 'scenes: [%s]\nwidth: 8\nthreshold: 20\nreference: ~\nsweep:\nseeds: null\nvariants:\n  - { sampler: jitter, light_sampler: ~ }\n' \
    "$S" >"$T/c.yaml"
rm -rf "$T/out"
"$WORKER" --quiet --out "$T/out" "$T/c.yaml" 2>"$T/err"; rc=$?
check "compare job with null optional keys renders (rc $rc: $(head -n 1 "$T/err"))" [ "$rc" -eq 0 ]
check "compare job: summary written" [ -s "$T/out/c/summary.csv" ]
printf 'width: 8\nscenes:\nvariants: [{ sampler: jitter }]\n' >"$T/c.yaml"
need "$T/c.yaml" 2:8 scenes
printf 'scenes: [%s]\nwidth: 8\nvariants: ~\n' "$S" >"$T/c.yaml"
need "$T/c.yaml" 3:11 variants
# scenes: an optional key null is its default; a required one needs a value
sed 's/vup: \[0, 1, 0\]/vup: ~/; s/scale: 10/scale: null/; s/^background: .*/background:/' "$S" >"$T/s.yaml"
printf 'scene: %s\nwidth: 8\nthreshold: 20\n' "$T/s.yaml" >"$T/j.yaml"
rm -rf "$T/out"
"$WORKER" --quiet --out "$T/out" "$T/j.yaml" 2>"$T/err"; rc=$?
check "scene with null optional keys renders (rc $rc: $(head -n 1 "$T/err"))" [ "$rc" -eq 0 ]
sed 's/radius: 50,/radius: ~,/' "$S" >"$T/s.yaml"
need "$T/s.yaml" 13:71 radius "$T/j.yaml"
sed 's/lookfrom: \[13, 2, 3\]/lookfrom: null/' "$S" >"$T/s.yaml"
need "$T/s.yaml" 2:21 lookfrom "$T/j.yaml"
finish
