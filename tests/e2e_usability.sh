#!/bin/sh
# End to end: small usability defects of issue 18, each a check that failed before its fix: a
# black image says so, --help tells of compare jobs and where the formats are written down, and
# the sidecar's sampling_share is a fraction. (An output extension naming no format and the
# "did you mean" for other renderers' words are cases of tests/bad/, run by e2e_bad.sh.)
. tests/lib.sh
TS='[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z' # a queue log line's time (ISO 8601, UTC)
root=$(pwd)

# 1. A rect light facing away from everything renders black: exit 0 still, but one warning line
#    naming the job (a whole render, a merge of parts, a queue job); turned around, no warning.
cat >"$T/away.yaml" <<'EOF'
camera: { lookfrom: [278, 278, -800], lookat: [278, 278, 0], vfov: 40 }
background: [0, 0, 0]
materials:
  white: { type: lambertian, albedo: [0.73, 0.73, 0.73] }
  lamp:  { type: light, emit: [15, 15, 15] }
objects:
  - { type: rect, plane: xz, min: [0, 0], max: [555, 555], at: 0, material: white }
  - { type: sphere, center: [278, 100, 278], radius: 100, material: white }
  - { type: rect, plane: xz, min: [213, 227], max: [343, 332], at: 554, material: lamp }
EOF
sed 's/, material: lamp/, flip: true, material: lamp/' "$T/away.yaml" >"$T/toward.yaml"
printf 'scene: away.yaml\nwidth: 16\nthreshold: 20\n' >"$T/dark.yaml"
printf 'scene: toward.yaml\nwidth: 16\nthreshold: 20\n' >"$T/lit.yaml"
warning='the image is entirely black (no light reaches the camera?'
"$WORKER" --quiet --out "$T/out" "$T/dark.yaml" 2>"$T/dark.err"; rc=$?
check "black image: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "black image: one warning naming the job ($(cat "$T/dark.err"))" \
    [ "$(grep -c "^dark: warning: $warning" "$T/dark.err")" -eq 1 ]
check "black image: the summary line and the warning, nothing else" [ "$(grep -c . "$T/dark.err")" -eq 2 ]
check "black image: still written" [ -s "$T/out/dark/dark.png" ]
"$WORKER" --quiet --out "$T/out" "$T/lit.yaml" 2>"$T/lit.err"; rc=$?
check "light turned to the scene: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "light turned to the scene: no warning ($(cat "$T/lit.err"))" sh -c "! grep -q warning '$T/lit.err'"
for i in 0 1; do "$WORKER" --quiet --out "$T/parts" --part $i/2 "$T/dark.yaml" 2>/dev/null; done
"$WORKER" --quiet --out "$T/parts" merge "$T/dark.yaml" 2>"$T/merge.err"; rc=$?
check "black parts merged: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "black parts merged: the warning ($(cat "$T/merge.err"))" grep -q "^dark: warning: $warning" "$T/merge.err"
mkdir -p "$T/q"
printf 'scene: %s/away.yaml\nwidth: 8\nthreshold: 50\n' "$T" >"$T/q/qdark.yaml"
"$WORKER" --quiet --queue "$T/q" --once 2>"$T/q.err"; rc=$?
check "black queue job: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "black queue job: the warning ($(cat "$T/q.err"))" sh -c "grep -E '^$TS qdark\.yaml: qdark: warning: ' '$T/q.err' | grep -qF '$warning'"

# 1b. Issue 27: with another light lighting the scene (so the image is not black), a disk light
#     facing away from everything is named (its material, its line:col); turned around, nothing.
cat >"$T/two.yaml" <<'EOF'
camera: { lookfrom: [0, 2, -8], lookat: [0, 1, 0], vfov: 40 }
materials:
  white: { type: lambertian, albedo: [0.73, 0.73, 0.73] }
  lamp:  { type: light, emit: [15, 15, 15] }
  up:    { type: light, emit: [15, 15, 15] }
objects:
  - { type: rect, plane: xz, min: [-10, -10], max: [10, 10], at: 0, material: white }
  - { type: sphere, center: [0, 1, 0], radius: 1, material: white }
  - { type: disk, center: [0, 5, 0], toward: [0, 0, 0], radius: 1, material: lamp }
  - { type: disk, center: [0, 6, 0], toward: [0, 10, 0], radius: 1, material: up }
EOF
sed 's/toward: \[0, 10, 0\]/toward: [0, 0, 0]/' "$T/two.yaml" >"$T/two-lit.yaml"
printf 'scene: two.yaml\nwidth: 16\nthreshold: 20\n' >"$T/twoaway.yaml"
printf 'scene: two-lit.yaml\nwidth: 16\nthreshold: 20\n' >"$T/twolit.yaml"
"$WORKER" --quiet --out "$T/out" "$T/twoaway.yaml" 2>"$T/two.err"; rc=$?
check "a disk facing away, another lighting: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "a disk facing away: named by material and line:col ($(cat "$T/two.err"))" \
    grep -qF "twoaway: warning: $T/two.yaml:10:5: the disk light (material \"up\") faces away from everything in the scene" "$T/two.err"
check "a disk facing away: not called black" sh -c "! grep -q 'entirely black' '$T/two.err'"
check "a disk facing away: the summary line and the warning" [ "$(grep -c . "$T/two.err")" -eq 2 ]
"$WORKER" --quiet --out "$T/out" "$T/twolit.yaml" 2>"$T/twolit.err"; rc=$?
check "both disks lighting: no warning ($(cat "$T/twolit.err"))" sh -c "[ $rc -eq 0 ] && ! grep -q warning '$T/twolit.err'"

# 4. --help says what a compare job is (a job with variants:), names the queue, diff and points,
#    and where the job and scene formats are written down.
"$WORKER" --help >"$T/help.out" 2>"$T/help.err"; rc=$?
check "--help: exit 0 (got $rc), nothing on stderr" sh -c "[ $rc -eq 0 ] && [ ! -s '$T/help.err' ]"
for want in 'compare job is a job file with variants:' 'report.html' '--queue DIR' 'worker diff' \
    'worker points' 'formats: docs/job-format.md, docs/scene-format.md' 'docs/compare.md' 'docs/farm.md' \
    'docs/samplers.md'; do
    check "--help mentions '$want'" grep -qF -- "$want" "$T/help.out"
done

# 4b. Every subcommand takes --help (and -h): its usage on stdout, exit 0, nothing on stderr.
for sub in diff points verdict merge status requeue; do
    for h in --help -h; do
        "$WORKER" $sub $h >"$T/sub.out" 2>"$T/sub.err"; rc=$?
        check "worker $sub $h: exit 0 (got $rc: $(head -c 200 "$T/sub.err"))" \
            eval '[ $rc -eq 0 ] && [ ! -s "$T/sub.err" ] && grep -q "usage: worker $sub" "$T/sub.out"'
    done
done

# 5. The sidecar's sampling_share is a fraction of the render processes' CPU time, and
#    sampler_s a part of cpu_s: a fresh Poisson set per pixel at a small threshold (drawing is
#    most of the time) over many processes, rendered whole and as merged parts (whose share was
#    the sum over each part's processes over the parts' wall times: 3.7 here).
printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nheight: 8\nsampler: poisson\nthreshold: 0.7\nlight_sampler: poisson\nprocesses: 4\n' \
    "$root" >"$T/share.yaml"
share_ok() { # share_ok SIDECAR: 0 <= sampling_share <= 1 and sampler_s <= cpu_s
    awk '/"cpu_s":/ && !c { c = $2 + 0 } /"sampler_s":/ { s = $2 + 0 } /"sampling_share":/ { f = $2 + 0 }
         END { exit !(f > 0 && f <= 1 && s <= c) }' FS='[:,] *' "$1"
}
"$WORKER" --quiet --out "$T/share" "$T/share.yaml" 2>/dev/null
check "sampling_share within [0, 1] ($(grep -o '"sampling_share": [^,]*' "$T/share/share/share.json"))" \
    share_ok "$T/share/share/share.json"
rm -rf "$T/share"
for i in 0 1; do "$WORKER" --quiet --out "$T/share" --part $i/2 "$T/share.yaml" 2>/dev/null; done
"$WORKER" --quiet --out "$T/share" merge "$T/share.yaml" 2>/dev/null
check "merged parts: sampling_share within [0, 1] ($(grep -o '"sampling_share": [^,]*' "$T/share/share/share.json"))" \
    share_ok "$T/share/share/share.json"
finish
