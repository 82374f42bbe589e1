#!/bin/sh
# End to end: resume. A job whose image and sidecar exist and record the same job hash is
# skipped with one line; --force renders it again; a changed job file, scene file or texture
# image renders.
. tests/lib.sh
TS='[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z' # a queue log line's time (ISO 8601, UTC)
root=$(pwd)

ino() { ls -i "$1" | cut -d' ' -f1; }
cp "$root/scenes/checker.yaml" "$T/scene.yaml"
printf 'scene: scene.yaml\nwidth: 16\nheight: 16\nthreshold: 50\nlight_threshold: 50\n' >"$T/r.yaml"
"$WORKER" --out "$T/out" "$T/r.yaml" 2>"$T/1.err"; rc=$?
check "first run renders (exit $rc)" grep -q "^r: 16x16" "$T/1.err"
check "sidecar records the job hash" grep -Eq '"job_hash": "[0-9a-f]{16}"' "$T/out/r/r.json"
png=$(ino "$T/out/r/r.png"); json=$(ino "$T/out/r/r.json")

"$WORKER" --out "$T/out" "$T/r.yaml" 2>"$T/2.err"; rc=$?
check "re-run: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "re-run: one line saying skipped" sh -c "[ \$(wc -l <'$T/2.err') -eq 1 ] && grep -q '^r: up to date (.*r.png, same job hash), skipped; --force renders it again' '$T/2.err'"
check "re-run: image untouched" [ "$(ino "$T/out/r/r.png")" = "$png" ]
check "re-run: sidecar untouched" [ "$(ino "$T/out/r/r.json")" = "$json" ]

"$WORKER" --force --out "$T/out" "$T/r.yaml" 2>"$T/3.err"
check "--force: renders" grep -q "^r: 16x16" "$T/3.err"
check "--force: image rewritten" [ "$(ino "$T/out/r/r.png")" != "$png" ]

png=$(ino "$T/out/r/r.png")
echo "# a comment changes the file" >>"$T/r.yaml"
"$WORKER" --out "$T/out" "$T/r.yaml" 2>"$T/4.err"
check "changed job file: renders" grep -q "^r: 16x16" "$T/4.err"
check "changed job file: image rewritten" [ "$(ino "$T/out/r/r.png")" != "$png" ]

echo "# the scene changed too" >>"$T/scene.yaml"
"$WORKER" --out "$T/out" "$T/r.yaml" 2>"$T/5.err"
check "changed scene file: renders" grep -q "^r: 16x16" "$T/5.err"
"$WORKER" --out "$T/out" "$T/r.yaml" 2>"$T/6.err"
check "then current again: skipped" grep -q "^r: up to date" "$T/6.err"

rm "$T/out/r/r.png"
"$WORKER" --out "$T/out" "$T/r.yaml" 2>"$T/7.err"
check "image missing: renders" grep -q "^r: 16x16" "$T/7.err"
rm "$T/out/r/r.json"
"$WORKER" --out "$T/out" "$T/r.yaml" 2>"$T/8.err"
check "sidecar missing: renders" grep -q "^r: 16x16" "$T/8.err"

# a scene's image texture is one of its inputs: a changed texture makes the image stale
mkdir -p "$T/tex/textures"
cp "$root/scenes/cornell.yaml" "$T/tex/scene.yaml"
cp "$root/scenes/textures/planet.png" "$T/tex/textures/planet.png"
printf 'scene: scene.yaml\nwidth: 8\nheight: 8\nthreshold: 50\nlight_threshold: 50\n' >"$T/tex/t.yaml"
"$WORKER" --out "$T/tout" "$T/tex/t.yaml" 2>"$T/t1.err"
check "textured scene: renders" grep -q "^t: 8x8" "$T/t1.err"
"$WORKER" --out "$T/tout" "$T/tex/t.yaml" 2>"$T/t2.err"
check "textured scene, same inputs: skipped" grep -q "^t: up to date" "$T/t2.err"
cp "$root/tests/golden/checker-jitter.png" "$T/tex/textures/planet.png"
"$WORKER" --out "$T/tout" "$T/tex/t.yaml" 2>"$T/t3.err"
check "changed texture image: renders" grep -q "^t: 8x8" "$T/t3.err"

# the reference image is an input too: a replaced reference must not leave the old error figures
printf 'scene: scene.yaml\nwidth: 16\nheight: 16\nthreshold: 50\nlight_threshold: 50\nreference: ref.png\n' >"$T/ref.yaml"
cp "$T/out/r/r.png" "$T/ref.png"
"$WORKER" --out "$T/out" "$T/ref.yaml" 2>"$T/r1.err"
check "with a reference: renders" grep -q "^ref: 16x16" "$T/r1.err"
"$WORKER" --out "$T/out" "$T/ref.yaml" 2>"$T/r2.err"
check "with the same reference: skipped" grep -q "^ref: up to date" "$T/r2.err"
rmse1=$(grep '"rmse"' "$T/out/ref/ref.json")
printf 'scene: scene.yaml\nwidth: 16\nheight: 16\nthreshold: 50\nlight_threshold: 50\nseed: 9\n' >"$T/other.yaml"
"$WORKER" --out "$T/out" "$T/other.yaml" 2>/dev/null
cp "$T/out/other/other.png" "$T/ref.png"
"$WORKER" --out "$T/out" "$T/ref.yaml" 2>"$T/r3.err"
check "changed reference image: renders" grep -q "^ref: 16x16" "$T/r3.err"
check "changed reference image: new error figures" [ "$(grep '"rmse"' "$T/out/ref/ref.json")" != "$rmse1" ]

# in a queue: a finished job put back is skipped and filed as done; --force renders it
Q=$T/q; mkdir -p "$Q"
sed 's|^scene: .*|scene: ../scene.yaml|' "$T/r.yaml" >"$Q/r.yaml"
"$WORKER" --queue "$Q" --once 2>"$T/q1.err"
check "queue: first run renders" grep -Eq "^$TS r\.yaml: r: 16x16" "$T/q1.err"
png=$(ino "$Q/done/r/r.png")
cp "$Q/done/r.yaml" "$Q/"
"$WORKER" --queue "$Q" --once 2>"$T/q2.err"; rc=$?
check "queue: re-queued job skipped (exit $rc)" grep -Eq "^$TS r\.yaml: up to date in .*done/r/ \(same job hash\), skipped" "$T/q2.err"
check "queue: skipped job filed as done" sh -c "[ -f '$Q/done/r.yaml' ] && [ ! -e '$Q/r.yaml' ]"
check "queue: image untouched" [ "$(ino "$Q/done/r/r.png")" = "$png" ]
cp "$Q/done/r.yaml" "$Q/"
"$WORKER" --queue "$Q" --once --force 2>"$T/q3.err"
check "queue --force: renders" grep -Eq "^$TS r\.yaml: r: 16x16" "$T/q3.err"
finish
