#!/bin/sh
# End to end for the shipped scenes: the generated files are reproducible from their committed
# generators, every job in jobs/ renders (shrunk), light_sampling is a job key, image textures
# resolve beside their scene and respect the size limit, and `worker diff --block` works.
. tests/lib.sh
root=$(pwd)
TOOLS_DIR=${TOOLS_DIR:-$root/build/tools}

# 1. make scenes reproduces the committed files.
"$TOOLS_DIR/gen_final" "$T/final.yaml"; rc=$?
check "gen_final runs (exit $rc)" [ "$rc" -eq 0 ]
check "scenes/final.yaml is what tools/gen_final.c writes" cmp -s "$T/final.yaml" scenes/final.yaml
"$TOOLS_DIR/gen_planet" "$T/planet.png"; rc=$?
check "gen_planet runs (exit $rc)" [ "$rc" -eq 0 ]
# (0.001 forgives a last-bit libm difference flipping a few texels by one level, nothing more)
"$WORKER" diff scenes/textures/planet.png "$T/planet.png" --max-rmse 0.001 >"$T/planet.diff" 2>&1; rc=$?
check "scenes/textures/planet.png has the pixels tools/gen_planet.c bakes (exit $rc)" [ "$rc" -eq 0 ]
check "final.yaml has 400 ground boxes" [ "$(grep -c 'type: box' scenes/final.yaml)" -eq 400 ]
check "final.yaml has 1000 cluster spheres" [ "$(grep -c 'rotate_y: 15' scenes/final.yaml)" -eq 1000 ]

# 2. every job in jobs/ renders (shrunk to 24x24 and a few samples) and every scene has a job.
for j in jobs/*.yaml; do
    n=$(basename "$j" .yaml)
    grep -qE '^(variants|studies):' "$j" && continue # compare jobs and suites: e2e_compare renders them shrunk
    sed -e 's/^width:.*/width: 24/' -e 's/^height:.*/height: 24/' -e 's/^threshold:.*/threshold: 50/' \
        -e 's/^light_threshold:.*/light_threshold: 50/' -e "s|^scene: \(.*\)|scene: $root/scenes/\1.yaml|" \
        "$j" >"$T/$n.yaml"
    "$WORKER" --quiet --out "$T/jobs" "$T/$n.yaml" 2>"$T/$n.err"; rc=$?
    check "$j renders (exit $rc: $(head -n 1 "$T/$n.err"))" [ "$rc" -eq 0 ]
    check "$j: image written" [ -s "$T/jobs/$n/$n.png" ]
    check "$j: sidecar records light_sampling" grep -q '"light_sampling": true' "$T/jobs/$n/$n.json"
done
for s in scenes/*.yaml; do
    n=$(basename "$s" .yaml)
    check "scene $n has a job in jobs/" grep -q "^scene: $n\$" jobs/*.yaml
done

# 3. light_sampling: false renders, is recorded, and changes the samples drawn; bad values fail.
job() { { echo "scene: $root/scenes/cornell-book3.yaml"; for l in "$@"; do echo "$l"; done; } >"$T/ls.yaml"; }
job "width: 16" "threshold: 50" "light_sampling: false"
"$WORKER" --quiet --out "$T/off" "$T/ls.yaml" 2>"$T/ls.err"; rc=$?
check "light_sampling: false renders (exit $rc)" [ "$rc" -eq 0 ]
check "sidecar records light_sampling false" grep -q '"light_sampling": false' "$T/off/ls/ls.json"
check "no light sample sets drawn with light sampling off" grep -q '"light_sample_sets": 0' "$T/off/ls/ls.json"
rejects() { # rejects KEY VALUE MESSAGE: a job with KEY: VALUE exits 2, says MESSAGE, writes nothing
    job "width: 16" "$1: $2"
    rm -rf "$T/bad"
    "$WORKER" --quiet --out "$T/bad" "$T/ls.yaml" 2>"$T/ls.err"; rc=$?
    check "$1: $2 exits 2 (got $rc)" [ "$rc" -eq 2 ]
    check "$1 error names file:line:col ($3)" grep -q "$3" "$T/ls.err"
    check "$1 error writes nothing" [ ! -e "$T/bad" ]
}
rejects light_sampling maybe "ls.yaml:3:17: light_sampling: must be"

# 3b. integrator: nee renders, is recorded, traces shadow rays (without roulette, more segments
# than the mixture's for the same samples), differs from the mixture; bad values fail with
# file:line:col.
for integ in mixture nee; do
    job "name: $integ" "width: 16" "threshold: 25" "integrator: $integ"
    "$WORKER" --quiet --out "$T/integ" "$T/ls.yaml" 2>"$T/ls.err"; rc=$?
    check "integrator: $integ renders (exit $rc)" [ "$rc" -eq 0 ]
    check "sidecar records integrator $integ" grep -q "\"integrator\": \"$integ\"" "$T/integ/$integ/$integ.json"
done
segs() { sed -n '/"rays"/,/}/s/.*"total": \([0-9]*\).*/\1/p' "$1" | head -n 1; }
check "nee's image differs from the mixture's" sh -c "! cmp -s '$T/integ/nee/nee.png' '$T/integ/mixture/mixture.png'"
# russian_roulette: on by default with nee, off with the mixture; off, nee's paths run longer
check "sidecar records russian_roulette on with nee" grep -q '"russian_roulette": "on"' "$T/integ/nee/nee.json"
check "sidecar records russian_roulette off with the mixture" \
    grep -q '"russian_roulette": "off"' "$T/integ/mixture/mixture.json"
job "name: nee-rroff" "width: 16" "threshold: 25" "integrator: nee" "russian_roulette: off"
"$WORKER" --quiet --out "$T/integ" "$T/ls.yaml" 2>"$T/ls.err"; rc=$?
check "russian_roulette: off renders (exit $rc)" [ "$rc" -eq 0 ]
check "sidecar records russian_roulette off" grep -q '"russian_roulette": "off"' "$T/integ/nee-rroff/nee-rroff.json"
check "nee without roulette traces more segments than the mixture ($(segs "$T/integ/nee-rroff/nee-rroff.json") vs $(segs "$T/integ/mixture/mixture.json"))" \
    [ "$(segs "$T/integ/nee-rroff/nee-rroff.json")" -gt "$(segs "$T/integ/mixture/mixture.json")" ]
check "nee without roulette traces more segments ($(segs "$T/integ/nee-rroff/nee-rroff.json") vs $(segs "$T/integ/nee/nee.json"))" \
    [ "$(segs "$T/integ/nee-rroff/nee-rroff.json")" -gt "$(segs "$T/integ/nee/nee.json")" ]
rejects russian_roulette maybe "ls.yaml:3:19: russian_roulette: must be off or on"
# The roulette is a weight window at 1/2: inside a closed white sphere (no light: only the path
# lengths count) with max_depth 3, the one roulette (after the second scatter) meets a throughput
# of albedo^2: 0.75^2 >= 1/2 never dies (the same segments as without roulette); 0.7^2 < 1/2 may.
for a in 0.75 0.7; do
    printf '%s\n' "camera: { lookfrom: [0, 0, 0], lookat: [0, 0, -1], vup: [0, 1, 0], vfov: 60, aperture: 0, focus_dist: 1 }" \
        "background: [0, 0, 0]" "materials: { wall: { type: lambertian, albedo: [$a, $a, $a] } }" \
        "objects: [{ type: sphere, center: [0, 0, 0], radius: 10, material: wall }]" >"$T/ww-$a-scene.yaml"
    for rr in on off; do
        printf '%s\n' "name: ww-$a-$rr" "scene: $T/ww-$a-scene.yaml" "width: 16" "threshold: 25" "max_depth: 3" \
            "integrator: nee" "russian_roulette: $rr" >"$T/ww.yaml"
        "$WORKER" --quiet --out "$T/ww" "$T/ww.yaml" 2>"$T/ww.err" || echo "ww-$a-$rr: $(cat "$T/ww.err")"
    done
done
check "roulette spares a throughput of 0.75^2 (segments $(segs "$T/ww/ww-0.75-on/ww-0.75-on.json") on, $(segs "$T/ww/ww-0.75-off/ww-0.75-off.json") off)" \
    [ "$(segs "$T/ww/ww-0.75-on/ww-0.75-on.json")" -eq "$(segs "$T/ww/ww-0.75-off/ww-0.75-off.json")" ]
check "roulette may end a throughput of 0.7^2 (segments $(segs "$T/ww/ww-0.7-on/ww-0.7-on.json") on, $(segs "$T/ww/ww-0.7-off/ww-0.7-off.json") off)" \
    [ "$(segs "$T/ww/ww-0.7-on/ww-0.7-on.json")" -lt "$(segs "$T/ww/ww-0.7-off/ww-0.7-off.json")" ]
# The studies of `make run` (soft-shadows, aliasing, cost, error-look) render nee at max_depth 2:
# no path scatters twice, so roulette never fires and their images, hence rankings, are the same
# bytes with it on or off.
for rr in on off; do
    printf '%s\n' "name: md2-$rr" "scene: $root/scenes/checker.yaml" "width: 16" "threshold: 25" "max_depth: 2" \
        "integrator: nee" "sampler_dims: all" "sampler: sobol" "russian_roulette: $rr" "output: md2-$rr.pfm" >"$T/md2.yaml"
    "$WORKER" --quiet --out "$T/md2" "$T/md2.yaml" 2>"$T/md2.err" || echo "md2-$rr: $(cat "$T/md2.err")"
done
check "max_depth 2: the same bytes with roulette on and off" cmp -s "$T/md2/md2-on/md2-on.pfm" "$T/md2/md2-off/md2-off.pfm"
# a compare variant takes russian_roulette too: its images named for it, each sidecar as applied
printf '%s\n' "name: rr" "scenes: [$root/scenes/cornell-book3.yaml]" "width: 8" "integrator: nee" \
    "reference: { sampler: jitter, threshold: 25 }" "seeds: [1]" "sweep: { threshold: [50] }" "variants:" \
    "  - { sampler: jitter }" "  - { sampler: jitter, russian_roulette: off }" >"$T/rr.yaml"
"$WORKER" --quiet --out "$T/rr" "$T/rr.yaml" 2>"$T/rr.err"; rc=$?
check "a compare job with a russian_roulette variant runs (exit $rc)" [ "$rc" -eq 0 ]
check "the variant's sidecar records russian_roulette off" \
    grep -q '"russian_roulette": "off"' "$T/rr/rr/cornell-book3-jitter-rouletteoff-t50-s1.json"
check "nee's default variant records russian_roulette on" \
    grep -q '"russian_roulette": "on"' "$T/rr/rr/cornell-book3-jitter-t50-s1.json"
for dims in pixel_light all; do
    job "name: d-$dims" "width: 16" "threshold: 25" "sampler: jitter" "sampler_dims: $dims"
    "$WORKER" --quiet --out "$T/dims" "$T/ls.yaml" 2>"$T/ls.err"; rc=$?
    check "sampler_dims: $dims renders (exit $rc)" [ "$rc" -eq 0 ]
    check "sidecar records sampler_dims $dims" grep -q "\"sampler_dims\": \"$dims\"" "$T/dims/d-$dims/d-$dims.json"
done
check "sampler_dims: all's image differs from pixel_light's" \
    sh -c "! cmp -s '$T/dims/d-all/d-all.png' '$T/dims/d-pixel_light/d-pixel_light.png'"
rejects sampler_dims every "ls.yaml:3:15: sampler_dims: must be pixel_light or all"
rejects integrator path "ls.yaml:3:13: integrator: must be mixture or nee"

# 4. An image texture resolves beside its scene file wherever the job runs from.
mkdir -p "$T/elsewhere/scenes/textures" "$T/cwd"
cp scenes/cornell.yaml "$T/elsewhere/scenes/" && cp scenes/textures/planet.png "$T/elsewhere/scenes/textures/"
printf 'scene: ../scenes/cornell.yaml\nwidth: 12\nthreshold: 50\nlight_threshold: 50\n' >"$T/elsewhere/jobs.yaml"
mkdir -p "$T/elsewhere/jobs" && mv "$T/elsewhere/jobs.yaml" "$T/elsewhere/jobs/tex.yaml"
(cd "$T/cwd" && "$WORKER" --quiet --out "$T/texout" "$T/elsewhere/jobs/tex.yaml" 2>"$T/tex.err"); rc=$?
check "texture found relative to the scene file (exit $rc: $(head -n 1 "$T/tex.err"))" [ "$rc" -eq 0 ]

# 4b. A bare scene name in a job file anywhere, run from anywhere: the scenes shipped with the
# program, beside its binary (bin/worker in a checkout: ../scenes) or installed
# (PREFIX/bin/worker: PREFIX/share/worker/scenes), textures included.
for layout in checkout installed; do
    p="$T/$layout"
    case $layout in
    checkout) sd="$p/scenes" ;;
    installed) sd="$p/share/worker/scenes" ;;
    esac
    mkdir -p "$p/bin" "$sd/textures" "$T/jobs-$layout" "$T/cwd-$layout"
    cp "$WORKER" "$p/bin/worker" && cp scenes/cornell.yaml "$sd/" && cp scenes/textures/planet.png "$sd/textures/"
    printf 'scene: cornell\nwidth: 12\nthreshold: 50\nlight_threshold: 50\n' >"$T/jobs-$layout/bare.yaml"
    (cd "$T/cwd-$layout" && "$p/bin/worker" --quiet --out "$T/out-$layout" "$T/jobs-$layout/bare.yaml" 2>"$T/bare.err"); rc=$?
    check "$layout: a bare scene name finds the shipped scene (exit $rc: $(head -n 1 "$T/bare.err"))" [ "$rc" -eq 0 ]
    check "$layout: and renders" [ -s "$T/out-$layout/bare/bare.png" ]
    rm -f "$sd/cornell.yaml"
    (cd "$T/cwd-$layout" && "$p/bin/worker" --quiet --out "$T/none-$layout" "$T/jobs-$layout/bare.yaml" 2>"$T/bare.err"); rc=$?
    check "$layout: without it exits 2 (got $rc)" [ "$rc" -eq 2 ]
    check "$layout: and names the shipped place looked in" grep -q "nor at .*$sd/cornell.yaml" "$T/bare.err"
done

# 4c. The job file's own scenes/ wins over the current folder's: a queue's job renders the same
# scene whichever folder its worker started in (here the current folder's cornell is black).
mkdir -p "$T/own/q/scenes/textures" "$T/own/cwd/scenes/textures"
cp scenes/cornell.yaml "$T/own/q/scenes/cornell.yaml"
cp scenes/textures/planet.png "$T/own/q/scenes/textures/" && cp scenes/textures/planet.png "$T/own/cwd/scenes/textures/"
sed 's/emit: \[[^]]*\]/emit: [0, 0, 0]/' scenes/cornell.yaml >"$T/own/cwd/scenes/cornell.yaml"
printf 'scene: cornell\nwidth: 12\nthreshold: 50\nlight_threshold: 50\n' >"$T/own/q/own.yaml"
(cd "$T/own/cwd" && "$WORKER" --quiet --out "$T/own/out" "$T/own/q/own.yaml" 2>"$T/own.err"); rc=$?
check "a bare scene beside the job renders from another folder (exit $rc)" [ "$rc" -eq 0 ]
check "... the job's own scene, not the current folder's" grep -q "\"scene\": \"$T/own/q/scenes/cornell.yaml\"" "$T/own/out/own/own.json"

# 4d. A texture that is a FIFO says so at its file: key (and is not opened: no hang)
mkfifo "$T/elsewhere/scenes/textures/fifo.png"
sed 's|file: textures/planet.png|file: textures/fifo.png|' scenes/cornell.yaml >"$T/elsewhere/scenes/fifo.yaml"
printf 'scene: %s\nwidth: 8\n' "$T/elsewhere/scenes/fifo.yaml" >"$T/fifo.yaml"
timeout 20 "$WORKER" --quiet --out "$T/fifoout" "$T/fifo.yaml" 2>"$T/fifo.err"; rc=$?
check "a FIFO texture: exit 2, named a FIFO at file: (got $rc: $(cat "$T/fifo.err"))" \
    eval '[ $rc -eq 2 ] && grep -q "fifo.yaml:[0-9]*:[0-9]*: file: .*fifo.png is a FIFO, not an image file" "$T/fifo.err"'

# 5. A texture over the size limit (4097 x 4097 pixels) is refused at its file: key.
{ printf 'P6\n4097 4097\n255\n'; head -c $((4097 * 4097 * 3)) /dev/zero; } >"$T/elsewhere/scenes/textures/huge.ppm"
sed 's|file: textures/planet.png|file: textures/huge.ppm|' scenes/cornell.yaml >"$T/elsewhere/scenes/huge.yaml"
printf 'scene: %s\nwidth: 8\n' "$T/elsewhere/scenes/huge.yaml" >"$T/huge.yaml"
rm -rf "$T/hugeout"
"$WORKER" --quiet --out "$T/hugeout" "$T/huge.yaml" 2>"$T/huge.err"; rc=$?
check "huge texture exits 2 (got $rc)" [ "$rc" -eq 2 ]
check "huge texture error at the file: key" grep -Eq "huge.yaml:8:[0-9]+: file: texture .*huge.ppm is 4097x4097, over the limit" "$T/huge.err"
check "huge texture writes nothing" [ ! -e "$T/hugeout" ]
rm -f "$T/elsewhere/scenes/textures/huge.ppm"

# 6. worker diff --block compares block means: noise between two seeds shrinks, a bad value fails.
for s in 1 2; do
    printf 'name: s%s\nscene: %s/scenes/checker.yaml\nwidth: 32\nheight: 32\nthreshold: 34\nseed: %s\n' \
        "$s" "$root" "$s" >"$T/s$s.yaml"
    "$WORKER" --quiet --out "$T/seeds" "$T/s$s.yaml" 2>/dev/null
done
a=$T/seeds/s1/s1.png; b=$T/seeds/s2/s2.png
px=$("$WORKER" diff "$a" "$b" | sed -n 's/^rmse //p')
bl=$("$WORKER" diff "$a" "$b" --block 8 | sed -n 's/^rmse //p')
check "block-8 rmse ($bl) is under half the per-pixel rmse ($px) between seeds" \
    awk -v a="$bl" -v b="$px" 'BEGIN { exit !(a > 0 && a < b / 2) }'
check "diff --block 1 equals plain diff" sh -c "[ \"\$('$WORKER' diff '$a' '$b' --block 1)\" = \"\$('$WORKER' diff '$a' '$b')\" ]"
"$WORKER" diff "$a" "$a" --block 4 --max-rmse 0 >/dev/null 2>&1; rc=$?
check "diff --block of an image with itself is 0 (exit $rc)" [ "$rc" -eq 0 ]
"$WORKER" diff "$a" "$b" --block 0 2>"$T/block.err"; rc=$?
check "diff --block 0 exits 2 (got $rc)" [ "$rc" -eq 2 ]
check "diff --block 0 says why" grep -q -- "--block needs a whole number" "$T/block.err"
# 7. Lights and sampled objects take rotate_y/translate (SPEC: "apply to any object") where the
#    transform folds into world-space geometry: the third book's box with its lamp placed by a
#    translate (and, as a second lamp form, a quarter turn) and its glass sphere by a translate
#    renders byte for byte as the scene that places them directly. A rect light turned by other
#    than a multiple of 90 degrees is refused at its rotate_y.
lamp_t='  - { type: rect, plane: xz, min: [-65, -52.5], max: [65, 52.5], at: 0, flip: true, material: lamp, translate: [278, 554, 279.5] }'
lamp_r='  - { type: rect, plane: xz, min: [-52.5, -65], max: [52.5, 65], at: 0, flip: true, material: lamp, rotate_y: 90, translate: [278, 554, 279.5] }'
glass_t='  - { type: sphere, center: [0, 0, 0], radius: 90, material: glass, sample: true, translate: [190, 90, 190] }'
for form in t r; do
    eval "lamp=\$lamp_$form"
    awk -v lamp="$lamp" -v glass="$glass_t" '/material: lamp/ { print lamp; next } /material: glass, sample/ { print glass; next } { print }' \
        scenes/cornell-book3.yaml >"$T/xl-$form.yaml"
    check "xl-$form: lamp and glass lines replaced" [ "$(grep -c 'translate: \[\(278\|190\)' "$T/xl-$form.yaml")" -eq 2 ]
done
for s in "$root/scenes/cornell-book3.yaml" "$T/xl-t.yaml" "$T/xl-r.yaml"; do
    n=$(basename "$s" .yaml)
    printf 'name: %s\nscene: %s\nwidth: 24\nthreshold: 25\nlight_threshold: 25\n' "$n" "$s" >"$T/job-$n.yaml"
    "$WORKER" --quiet --out "$T/xl" "$T/job-$n.yaml" 2>"$T/xl-$n.err"; rc=$?
    check "transformed lights: $n renders (exit $rc: $(head -n 1 "$T/xl-$n.err"))" [ "$rc" -eq 0 ]
done
check "a translated lamp and sphere render as placed directly" cmp -s "$T/xl/cornell-book3/cornell-book3.png" "$T/xl/xl-t/xl-t.png"
check "a quarter-turned lamp renders as placed directly" cmp -s "$T/xl/cornell-book3/cornell-book3.png" "$T/xl/xl-r/xl-r.png"
sed 's/rotate_y: 90/rotate_y: 45/' "$T/xl-r.yaml" >"$T/xl-45.yaml"
printf 'scene: %s\nwidth: 8\n' "$T/xl-45.yaml" >"$T/job-xl-45.yaml"
rm -rf "$T/xl45"
"$WORKER" --quiet --out "$T/xl45" "$T/job-xl-45.yaml" 2>"$T/xl-45.err"; rc=$?
check "a lamp turned 45 degrees exits 2 (got $rc)" [ "$rc" -eq 2 ]
check "and says why at its rotate_y" grep -q "xl-45.yaml:[0-9]*:[0-9]*: rotate_y: a light or sampled rect turns only by multiples of 90 degrees" "$T/xl-45.err"
check "and writes nothing" [ ! -e "$T/xl45" ]

finish
