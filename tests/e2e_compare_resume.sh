#!/bin/sh
# Resume for compare jobs: a re-run renders only the combinations that are missing; --force
# renders them all; a changed scene renders them again.
. tests/lib.sh
root=$(pwd)
cp scenes/checker.yaml "$T/checker.yaml"
cat >"$T/cmp.yaml" <<YAML
name: cmp
scenes: [$T/checker.yaml]
width: 16
reference: { sampler: jitter, threshold: 20 }
seeds: [1, 2]
sweep: { threshold: [50, 34] }
variants:
  - { sampler: jitter }
  - { sampler: random }
YAML
run() { "$WORKER" --quiet --out "$T/out" "$@" "$T/cmp.yaml" 2>"$T/err"; }
stamp() { ls -i "$T"/out/cmp/*.png | sort -k2; }
run; rc=$?
check "first run exits 0" [ "$rc" -eq 0 ]
check "first run renders 8 images" [ "$(ls "$T"/out/cmp/*.png | wc -l)" -eq 8 ]
stamp >"$T/first"
run; rc=$?
check "second run exits 0" [ "$rc" -eq 0 ]
check "second run says all 8 are current" grep -q "8 of them current" "$T/err"
stamp >"$T/second"
check "second run leaves every image untouched" cmp -s "$T/first" "$T/second"
check "summary.csv still has 8 rows with errors" [ "$(grep -c ',checker-' "$T/out/cmp/summary.csv")" -eq 8 ]
# wall_s (field 7) comes from each skipped image's sidecar: none is 0 or missing
check "skipped rows keep their timing" [ "$(awk -F, 'NR > 1 && $7 > 0' "$T/out/cmp/summary.csv" | wc -l)" -eq 8 ]
# the same --out spelled another way (relative, through ./): the same outputs, all current
(cd "$T" && "$WORKER" --quiet --out ./out/../out cmp.yaml 2>"$T/err")
check "--out spelled another way: all 8 current" grep -q "8 of them current" "$T/err"
sed -i 's/seeds: \[1, 2\]/seeds: [1, 2, 3]/' "$T/cmp.yaml"
run
check "a new seed renders only the 4 missing images" grep -q "12 images .*8 of them current" "$T/err"
check "12 images now" [ "$(ls "$T"/out/cmp/*.png | wc -l)" -eq 12 ]
run --force
check "--force renders them all" sh -c "! grep -q 'current' '$T/err'"
echo "# changed" >>"$T/checker.yaml"
run
check "a changed scene renders every image again" sh -c "! grep -q 'of them current' '$T/err'"
# a reference given as an image file: replacing its bytes (same path) makes every image stale
cat >"$T/cmpf.yaml" <<YAML
name: cmpf
scene: $T/checker.yaml
width: 16
reference: ref.png
variants:
  - { sampler: jitter, threshold: 50 }
YAML
cp "$T/out/cmp/checker-jitter-t50-s1.png" "$T/ref.png"
"$WORKER" --quiet --out "$T/out" "$T/cmpf.yaml" 2>"$T/f1"
"$WORKER" --quiet --out "$T/out" "$T/cmpf.yaml" 2>"$T/f2"
check "image reference, unchanged: current" grep -q "1 of them current" "$T/f2"
cp "$T/out/cmp/checker-jitter-t50-s2.png" "$T/ref.png"
"$WORKER" --quiet --out "$T/out" "$T/cmpf.yaml" 2>"$T/f3"; rc=$?
check "image reference replaced: rendered and scored again (exit $rc)" \
    sh -c "[ $rc -eq 0 ] && grep -q '^cmpf: 1 image ' '$T/f3' && ! grep -q 'of them current' '$T/f3'"
finish
