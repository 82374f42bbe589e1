#!/bin/sh
# End to end, SPEC.md as a black box: its example job, compare job and scene copied verbatim (only
# paths and sizes adjusted), defaults it states, and what a user sees from another folder.
. tests/lib.sh
root=$(pwd)
mkdir -p "$T/jobs" "$T/scenes"
cp -r "$root/scenes/." "$T/scenes/"

# 1. SPEC's example job, verbatim: it parses to its last line (a missing ref.png is the one error,
#    at 14:12), then, sized down, renders with every key as written and scores against ref.png
cat >"$T/jobs/spec.yaml" <<'EOF'
name: cornell-poisson        # default: the file's stem
scene: ../scenes/cornell.yaml  # relative to this file; a bare name (cornell) = scenes/cornell.yaml
width: 300                   # default 300; height defaults to width / the camera's aspect
height: 300
sampler: poisson             # uniform | jitter | random | poisson   (pixel sampler)
threshold: 1                 # min spacing in a 100x100 domain, 0 < t <= 100
light_sampler: poisson       # same four names; default: same as sampler
light_threshold: 5           # default 5
max_depth: 50                # default 50
seed: 1                      # default 1
processes: 2                 # forked renderers, default 2; rows are split between them
format: png                  # png | ppm; default from output's extension, else png
output: cornell-poisson.png  # written under --out DIR/<name>/
reference: ref.png           # optional: an image to score against (path relative to this file)
EOF
(cd "$T" && "$WORKER" --out "$T/o1" jobs/spec.yaml 2>"$T/e1"); rc=$?
check "SPEC job without its ref.png: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "SPEC job without its ref.png: one line at 14:12 ($(cat "$T/e1"))" \
    sh -c "[ \$(wc -l <'$T/e1') -eq 1 ] && grep -q '^jobs/spec.yaml:14:12: reference: ' '$T/e1'"
check "SPEC job without its ref.png: nothing written" [ ! -e "$T/o1" ]
sed -e 's/^width: 300 /width: 24  /; s/^height: 300/height: 24 /; s/^threshold: 1 /threshold: 25/' \
    "$T/jobs/spec.yaml" >"$T/jobs/small.yaml"
grep -v '^reference:' "$T/jobs/small.yaml" | sed 's/^name: cornell-poisson/name: ref/' >"$T/jobs/ref.yaml"
(cd "$T" && "$WORKER" --out "$T/o1" jobs/ref.yaml 2>/dev/null)
cp "$T/o1/ref/cornell-poisson.png" "$T/jobs/ref.png"
(cd "$T" && "$WORKER" --out "$T/o1" jobs/small.yaml 2>"$T/e1"); rc=$?
s="$T/o1/cornell-poisson/cornell-poisson.json"
check "SPEC job (sized down) renders (got $rc: $(cat "$T/e1"))" [ "$rc" -eq 0 ]
check "SPEC job: image at --out DIR/<name>/<output>" [ -s "$T/o1/cornell-poisson/cornell-poisson.png" ]
for key in '"job": "cornell-poisson"' '"sampler": "poisson"' '"light_sampler": "poisson"' \
    '"light_threshold": 5' '"seed": 1' '"processes": 2' '"threshold": 25' '"rmse": 0,' '"relmse_eps": 0.01'; do
    check "SPEC job: sidecar has $key" grep -q "$key" "$s"
done
# ref.png is 8-bit: one warning line says the error is measured on 8-bit display values
check "SPEC job: the 8-bit reference's warning and the summary line are the only stderr lines (not a terminal)" \
    sh -c "[ \$(wc -l <'$T/e1') -eq 2 ] && grep -q '^cornell-poisson: warning: reference .*8-bit display values' '$T/e1'"
check "SPEC job: its error names the 8-bit domain" grep -q '"domain": "8-bit"' "$s"

# 2. defaults: width 300, height = width / the camera's aspect (rounded), name = the file's stem,
#    output <name>.png, light sampler = sampler, light_threshold 5, max_depth 50, seed 1, processes 2
printf 'scene: cornell\nthreshold: 100\nlight_threshold: 100\nmax_depth: 1\n' >"$T/jobs/plain.yaml"
(cd "$T" && "$WORKER" --quiet --out "$T/o2" jobs/plain.yaml 2>/dev/null); rc=$?
tr -d '\n' <"$T/o2/plain/plain.json" >"$T/flat.json"
check "width defaults to 300, cornell's aspect 1 gives 300 rows (exit $rc)" grep -q '"size": \[ *300, *300 *\]' "$T/flat.json"
printf 'scene: checker\nwidth: 8\nthreshold: 50\nsampler: jitter\n' >"$T/jobs/defaults.yaml"
(cd "$T" && "$WORKER" --quiet --out "$T/o2" jobs/defaults.yaml 2>/dev/null)
for key in '"job": "defaults"' '"image": "defaults.png"' '"light_sampler": "jitter"' '"light_threshold": 5' \
    '"max_depth": 50' '"seed": 1' '"processes": 2'; do
    check "defaults: sidecar has $key" grep -q "$key" "$T/o2/defaults/defaults.json"
done
for a in "2 8 4" "2 7 4" "0.75 8 11" "0.75 7 9" "2 1 1" "0.75 3 4"; do
    set -- $a
    sed "s/aspect: 1 }/aspect: $1 }/" "$root/scenes/cornell.yaml" >"$T/scenes/aspect.yaml"
    printf 'scene: aspect\nwidth: %s\nthreshold: 50\nlight_threshold: 50\n' "$2" >"$T/jobs/aspect.yaml"
    rm -rf "$T/o2/aspect"
    (cd "$T" && "$WORKER" --quiet --out "$T/o2" jobs/aspect.yaml 2>/dev/null)
    check "aspect $1, width $2: height $3" sh -c "head -c 24 '$T/o2/aspect/aspect.png' | od -An -tu1 | tr -s ' \n' ' ' | grep -q ' 0 0 0 $2 0 0 0 $3 *\$'"
done

# 3. processes above the row count: one process per row, the same bytes; a 1x1 image in either format
printf 'scene: checker\nwidth: 5\nheight: 3\nthreshold: 50\nprocesses: 8\n' >"$T/jobs/rows.yaml"
"$WORKER" --quiet --out "$T/o3" "$T/jobs/rows.yaml" 2>/dev/null; rc=$?
check "processes: 8 over 3 rows: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "processes: 8 over 3 rows: three processes recorded" [ "$(grep -c '"pixels"' "$T/o3/rows/rows.json")" -eq 3 ]
cp "$T/o3/rows/rows.png" "$T/rows8.png"
"$WORKER" --quiet --out "$T/o3" --processes 1 "$T/jobs/rows.yaml" 2>/dev/null
check "processes: 8 over 3 rows: the bytes of one process" cmp -s "$T/rows8.png" "$T/o3/rows/rows.png"
for f in png ppm; do
    printf 'scene: cornell\nwidth: 1\nheight: 1\nthreshold: 20\nsampler: poisson\nformat: %s\n' "$f" >"$T/jobs/one$f.yaml"
    "$WORKER" --quiet --out "$T/o3" "$T/jobs/one$f.yaml" 2>/dev/null; rc=$?
    check "1x1 $f: exit 0 (got $rc)" [ "$rc" -eq 0 ]
    "$WORKER" diff "$T/o3/one$f/one$f.$f" "$T/o3/one$f/one$f.$f" --max-rmse 0 >/dev/null 2>&1; rc=$?
    check "1x1 $f: a readable image (diff with itself exits $rc)" [ "$rc" -eq 0 ]
done
"$WORKER" diff "$T/o3/onepng/onepng.png" "$T/o3/oneppm/oneppm.ppm" --max-rmse 0 >/dev/null 2>&1; rc=$?
check "1x1: the PPM holds the PNG's pixel (diff exit $rc)" [ "$rc" -eq 0 ]
printf 'P6\n1 1\n255\n' >"$T/p6head"
check "1x1 ppm: P6 1 1 255 and three bytes" sh -c "[ \$(wc -c <'$T/o3/oneppm/oneppm.ppm') -eq 14 ] && head -c 11 '$T/o3/oneppm/oneppm.ppm' | cmp -s - '$T/p6head'"

# 4. output names: a bad one says what a plain file name is (".png" and "a b.png" have no '/')
for o in '.png' 'a b.png'; do
    printf 'scene: checker\nwidth: 8\noutput: "%s"\n' "$o" >"$T/jobs/outname.yaml"
    "$WORKER" --quiet --out "$T/o4" "$T/jobs/outname.yaml" 2>"$T/e4"; rc=$?
    check "output: \"$o\": exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "output: \"$o\": the error says what is allowed ($(cat "$T/e4"))" \
        grep -q "outname.yaml:3:9: output: must be .*letters, digits, '-', '_' or '.'.*not starting with '.'" "$T/e4"
done

# 5. worker points --svg to a place that cannot take it is bad usage (exit 2, one line), nothing on
#    stdout, as --out naming a file is for a job; a full disk stays exit 1 (not tested here)
: >"$T/afile"
mkdir -p "$T/adir"
for f in "$T/nofolder/p.svg" "$T/afile/p.svg" "$T/adir"; do
    "$WORKER" points jitter 20 --svg "$f" >"$T/p5.out" 2>"$T/p5.err"; rc=$?
    check "points --svg $f: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "points --svg $f: one line naming it ($(cat "$T/p5.err"))" \
        sh -c "[ \$(wc -l <'$T/p5.err') -eq 1 ] && grep -q -- '$f' '$T/p5.err'"
    check "points --svg $f: no points printed" [ ! -s "$T/p5.out" ]
done
if [ "$(id -u)" != 0 ]; then
    mkdir -p "$T/ro" && chmod a-w "$T/ro"
    "$WORKER" points jitter 20 --svg "$T/ro/p.svg" >/dev/null 2>&1; rc=$?
    check "points --svg into a read-only folder: exit 2 (got $rc)" [ "$rc" -eq 2 ]
fi

# 6. the queue's layout as SPEC states it: a job named apart from its file renders into
#    DIR/done/<name>/ and the file goes to DIR/done/X.yaml; an invalid job or compare job goes to
#    DIR/failed/X.yaml with a log, never attempted (the log says "attempts: 0" for both kinds)
Q="$T/q"; mkdir -p "$Q"
printf 'name: named\nscene: ../scenes/cornell.yaml\nwidth: 8\nthreshold: 50\nlight_threshold: 50\n' >"$Q/a.yaml"
printf 'scene: cornell\nthreshold: abc\n' >"$Q/bad.yaml"
printf 'name: cmp\nscene: cornell\nwidth: 4\nvariants:\n  - { sampler: stratified }\n' >"$Q/badcmp.yaml"
(cd "$T" && "$WORKER" --queue q --once 2>"$T/q.err"); rc=$?
check "queue: exit 2 with an invalid job among them (got $rc)" [ "$rc" -eq 2 ]
check "queue: DIR/done/<name>/ holds the image and sidecar" sh -c "[ -s '$Q/done/named/named.png' ] && [ -s '$Q/done/named/named.json' ]"
check "queue: DIR/done/X.yaml" [ -f "$Q/done/a.yaml" ]
check "queue: running/ is empty" [ -z "$(ls -A "$Q/running")" ]
for b in bad badcmp; do
    check "queue: invalid $b: DIR/failed/$b.yaml and its log" sh -c "[ -f '$Q/failed/$b.yaml' ] && [ -s '$Q/failed/$b.log' ]"
    check "queue: invalid $b: the log has the file:line:col" grep -q "^error: .*$b.yaml:[0-9]*:[0-9]*: " "$Q/failed/$b.log"
    check "queue: invalid $b: never attempted ($(grep attempts "$Q/failed/$b.log"))" grep -q '^attempts: 0$' "$Q/failed/$b.log"
done

# 7. progress: on a terminal (script(1) gives one) percent of rows, elapsed and ETA, then the summary;
#    with --quiet, or stderr not a terminal, only the summary line. No ETA is claimed before a row
#    is done (it printed "0% ... ETA 0.0 s")
printf 'scene: cornell\nwidth: 24\nthreshold: 20\nlight_threshold: 20\n' >"$T/jobs/prog.yaml"
if command -v script >/dev/null 2>&1; then
    script -qec "'$WORKER' --force --out '$T/o7' '$T/jobs/prog.yaml'" /dev/null >"$T/tty.out" 2>&1
    tr '\r' '\n' <"$T/tty.out" | grep . >"$T/tty.lines"
    check "terminal: a 100% line with elapsed and ETA" grep -Eq '^prog: 100% \(24/24 rows\) [0-9.]+ s elapsed, ETA [0-9.]+ s' "$T/tty.lines"
    check "terminal: the summary line last" sh -c "tail -n 1 '$T/tty.lines' | grep -q '^prog: 24x24 '"
    check "terminal: no ETA claimed at 0% ($(grep ' 0% ' "$T/tty.lines"))" sh -c "! grep -q ' 0% .*ETA 0.0 s' '$T/tty.lines'"
    script -qec "'$WORKER' --quiet --force --out '$T/o7' '$T/jobs/prog.yaml'" /dev/null >"$T/ttyq.out" 2>&1
    check "terminal, --quiet: the summary line only" sh -c "[ \$(tr '\\r' '\\n' <'$T/ttyq.out' | grep -c .) -eq 1 ] && grep -q '^prog: 24x24 ' '$T/ttyq.out'"
else
    echo "note: script(1) missing, progress on a terminal not checked"
fi
"$WORKER" --force --out "$T/o7" "$T/jobs/prog.yaml" 2>"$T/nt.err"
check "stderr not a terminal: the summary line only" sh -c "[ \$(wc -l <'$T/nt.err') -eq 1 ] && ! grep -q '%' '$T/nt.err'"

# 8. SPEC's compare job, its keys and layout verbatim (sizes and thresholds only made small): every
#    image with its sidecar, summary.csv, chart.svg and report.html under --out DIR/<name>/
cat >"$T/jobs/compare.yaml" <<'EOF'
name: compare
scenes: [checker, cornell]
width: 200
reference: { sampler: jitter, threshold: 0.5 }   # a converged render per scene, cached
seeds: [1, 2, 3]                                 # spread = stability
sweep: { threshold: [20, 10, 5, 2, 1] }          # points along each speed/accuracy curve
variants:
  - { sampler: poisson, light_sampler: poisson }
  - { sampler: jitter,  light_sampler: jitter }
  - { sampler: uniform, light_sampler: uniform }
  - { sampler: random,  light_sampler: random }
EOF
sed -i -e 's/^width: 200/width: 6  /; s/threshold: 0.5 }/threshold: 25 }/; s/\[20, 10, 5, 2, 1\]/[50, 34]/' \
    "$T/jobs/compare.yaml"
(cd "$T/jobs" && "$WORKER" --out "$T/o8" compare.yaml 2>"$T/e8"); rc=$?
check "SPEC compare job: exit 0 (got $rc: $(head -n 1 "$T/e8"))" [ "$rc" -eq 0 ]
check "SPEC compare job: one summary line (and the verdict's warnings)" [ "$(grep -vc ': warning: ' "$T/e8")" -eq 1 ]
check "SPEC compare job: the summary names the winner at equal CPU time" grep -q '; at equal CPU time: compare: ' "$T/e8"
check "SPEC compare job: verdict.json beside report.html" [ -s "$T/o8/compare/verdict.json" -a -s "$T/o8/compare/report.html" ]
n=$(ls "$T/o8/compare" | grep -c '\.png$')
check "SPEC compare job: 2 scenes x 4 variants x 2 thresholds x 3 seeds = 48 images (got $n)" [ "$n" -eq 48 ]
for f in summary.csv chart.svg report.html checker-poisson-t50-s1.json cornell-random-t34-s3.png; do
    check "SPEC compare job: $f" [ -s "$T/o8/compare/$f" ]
done
check "SPEC compare job: summary.csv has a header and 48 rows" [ "$(wc -l <"$T/o8/compare/summary.csv")" -eq 49 ]

# 9. SPEC's scene file, verbatim (its image texture copied beside it): every type and key it shows
mkdir -p "$T/spec_scene/textures"
cp "$root/scenes/textures/planet.png" "$T/spec_scene/textures/"
cat >"$T/spec_scene/scene.yaml" <<'EOF'
camera: { lookfrom: [278, 278, -800], lookat: [278, 278, 0], vup: [0, 1, 0],
          vfov: 40, aperture: 0, focus_dist: 10, shutter: [0, 1], aspect: 1 }  # vup, aperture, shutter, aspect (1) optional
background: [0, 0, 0]
textures:
  board:  { type: checker, odd: [0.2, 0.3, 0.1], even: [0.9, 0.9, 0.9], scale: 10 }
  marble: { type: noise, scale: 4 }
  planet: { type: image, file: textures/planet.png }      # PNG or PPM, relative to the scene
materials:
  white:  { type: lambertian, albedo: [0.73, 0.73, 0.73] }
  ground: { type: lambertian, texture: board }
  alu:    { type: metal, albedo: [0.8, 0.85, 0.88], fuzz: 0 }
  glass:  { type: dielectric, ior: 1.5 }
  lamp:   { type: light, emit: [15, 15, 15] }
  smoke:  { type: isotropic, albedo: [1, 1, 1] }
objects:
  - { type: sphere, center: [0, 1, 0], radius: 1, material: white }
  - { type: moving_sphere, center0: [0, 1, 0], center1: [0, 1.5, 0], radius: 1, material: white }
  - { type: rect, plane: yz, min: [0, 0], max: [555, 555], at: 555, material: white }  # xy | xz | yz
  - { type: box, min: [0, 0, 0], max: [120, 330, 120], material: white, rotate_y: 10, translate: [400, 0, 295] }
  - { type: disk, center: [278, 554, 279], toward: [278, 0, 279], radius: 60, material: lamp }
  - { type: cylinder, base: [0, 0, 0], top: [120, 120, 120], radius: 50, material: alu }
  - { type: triangle, vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], material: white }
  - { type: pyramid, apex: [0, 140, 0], base: [[-100, 0, -100], [140, 0, 0], [0, 0, 140]], material: white }
  - { type: medium, boundary: { type: sphere, center: [0, 0, 0], radius: 5000 }, density: 0.0001, material: smoke }
EOF
printf 'scene: ../spec_scene/scene.yaml\nwidth: 12\nthreshold: 50\nlight_threshold: 50\n' >"$T/jobs/specscene.yaml"
"$WORKER" --out "$T/o9" "$T/jobs/specscene.yaml" 2>"$T/e9"; rc=$?
check "SPEC scene: renders (got $rc: $(head -n 1 "$T/e9"))" [ "$rc" -eq 0 ]
check "SPEC scene: 12x12 image" [ -s "$T/o9/specscene/specscene.png" ]

# 10. from another folder: a bare scene name finds the shipped scene (scenes/ beside the program's bin/,
#     when this build has one), outputs go to ./out; a shipped job file by its path renders
mkdir -p "$T/far/away"
scene=checker
[ -d "$(dirname "$WORKER")/../scenes" ] || scene=$root/scenes/checker.yaml
printf 'scene: %s\nwidth: 8\nthreshold: 50\n' "$scene" >"$T/far/away/mine.yaml"
(cd "$T/far/away" && "$WORKER" --quiet mine.yaml 2>"$T/e10"); rc=$?
check "another folder: exit 0 (got $rc: $(head -n 1 "$T/e10"))" [ "$rc" -eq 0 ]
check "another folder: ./out/<name>/<name>.png and .json" \
    sh -c "[ -s '$T/far/away/out/mine/mine.png' ] && [ -s '$T/far/away/out/mine/mine.json' ]"
(cd "$T/far/away" && "$WORKER" --quiet "$root/jobs/cornell-book3.yaml" --out "$T/o10" 2>/dev/null); rc=$?
check "another folder: a shipped job by its path renders (got $rc)" [ -s "$T/o10/cornell-book3/cornell-book3.png" ]

# 11. worker diff: metrics of B against reference A on stdout, by hand for a 1x1 pair (reference
#     (128, 0, 0), image black: mse = (128/255)^2 / 3, relmse = v^2 / (v^2 + 0.01) / 3, psnr =
#     10 log10(1 / mse)); exit 1 only over --max-rmse (equal is not over), 2 for sizes that differ
printf 'P3 1 1 255 128 0 0' >"$T/ref1.ppm"
printf 'P3 1 1 255 0 0 0' >"$T/img1.ppm"
printf 'P3 2 1 255 0 0 0 0 0 0' >"$T/img2.ppm"
"$WORKER" diff "$T/ref1.ppm" "$T/img1.ppm" >"$T/d.out" 2>"$T/d.err"; rc=$?
check "diff: exit 0 without --max-rmse (got $rc)" [ "$rc" -eq 0 ]
check "diff: mse, rmse, relmse, psnr by hand ($(tr '\n' ' ' <"$T/d.out"))" awk '
    /^mse / {m = $2} /^rmse / {r = $2} /^relmse / {l = $2} /^psnr / {p = $2}
    function off(a, b) { return (a - b) / b > 1e-5 || (b - a) / b > 1e-5 }
    END { exit off(m, 0.0839882097) || off(r, 0.2898071939) || off(l, 0.3206089692) || off(p, 10.7578168) }' "$T/d.out"
"$WORKER" diff "$T/ref1.ppm" "$T/img1.ppm" --max-rmse 0.2899 >/dev/null 2>&1; rc=$?
check "diff --max-rmse above the rmse: exit 0 (got $rc)" [ "$rc" -eq 0 ]
"$WORKER" diff "$T/ref1.ppm" "$T/img1.ppm" --max-rmse 0.2897 >/dev/null 2>"$T/d.err"; rc=$?
check "diff --max-rmse below the rmse: exit 1 (got $rc)" [ "$rc" -eq 1 ]
check "diff over --max-rmse: one line saying so" sh -c "[ \$(wc -l <'$T/d.err') -eq 1 ] && grep -q 'max-rmse' '$T/d.err'"
printf 'P3 2 1 255 0 0 0 255 255 255' >"$T/ref2.ppm"
printf 'P3 2 1 255 255 255 255 0 0 0' >"$T/inv2.ppm"
"$WORKER" diff "$T/ref2.ppm" "$T/inv2.ppm" --max-rmse 1 >/dev/null 2>&1; rc=$?
check "diff: rmse 1 with --max-rmse 1 is not over (exit $rc)" [ "$rc" -eq 0 ]
"$WORKER" diff "$T/ref1.ppm" "$T/img2.ppm" >/dev/null 2>"$T/d.err"; rc=$?
check "diff of two sizes: exit 2, one line (got $rc)" sh -c "[ $rc -eq 2 ] && [ \$(wc -l <'$T/d.err') -eq 1 ]"

# 12. a job without name: is named for its file's stem; a stem that cannot name a folder under --out
#     ("..yaml" gave ".", writing OUT/..png; "...yaml" gave "..", writing beside --out, outside it) is
#     refused, exit 2, naming the file, with nothing written
mkdir -p "$T/stems/in"
for f in '..yaml' '...yaml' '.hidden.yaml'; do
    printf 'scene: %s\nwidth: 4\nthreshold: 50\n' "$root/scenes/checker.yaml" >"$T/stems/in/$f"
    rm -rf "$T/stems/in/o"
    (cd "$T/stems/in" && "$WORKER" --quiet --out o "./$f" 2>"$T/e12"); rc=$?
    check "job file $f: exit 2 (got $rc: $(cat "$T/e12"))" [ "$rc" -eq 2 ]
    check "job file $f: one line naming it and name:" sh -c "[ \$(wc -l <'$T/e12') -eq 1 ] && grep -q -- '^\\./$f:1:1: name: ' '$T/e12'"
    check "job file $f: nothing written" sh -c "[ ! -e '$T/stems/in/o' ] && [ -z \"\$(ls '$T/stems' | grep -v '^in\$')\" ] && [ -z \"\$(ls '$T/stems/in' | grep -v yaml)\" ]"
done
printf 'scene: %s\nwidth: 4\nthreshold: 50\nvariants:\n  - { sampler: jitter }\n' "$root/scenes/checker.yaml" >"$T/stems/in/...yaml"
(cd "$T/stems/in" && "$WORKER" --quiet --out o ./...yaml 2>"$T/e12"); rc=$?
check "compare job file ...yaml: exit 2 naming the stem (got $rc: $(cat "$T/e12"))" \
    sh -c "[ $rc -eq 2 ] && grep -q '^\./\.\.\.yaml:1:1: name: ' '$T/e12' && [ ! -e '$T/stems/in/o' ]"
printf 'name: fine\nscene: %s\nwidth: 4\nthreshold: 50\n' "$root/scenes/checker.yaml" >"$T/stems/in/...yaml"
(cd "$T/stems/in" && "$WORKER" --quiet --out o ./...yaml 2>/dev/null); rc=$?
check "job file ...yaml with a name: renders into o/fine/ (got $rc)" [ -s "$T/stems/in/o/fine/fine.png" ]
cp "$T/stems/in/..yaml" "$T/stems/in/my job.yaml"
(cd "$T/stems/in" && "$WORKER" --quiet --out o "my job.yaml" 2>/dev/null); rc=$?
check "job file 'my job.yaml': named for its stem as before (got $rc)" [ -s "$T/stems/in/o/my job/my job.png" ]

# 13. --out DIR/ (a shell's completion adds the slash) names the same paths as --out DIR: the summary
#     line said DIR//<name>/<name>.png
printf 'scene: checker\nwidth: 4\nthreshold: 50\n' >"$T/jobs/slash.yaml"
"$WORKER" --out "$T/o13//" "$T/jobs/slash.yaml" 2>"$T/e13"; rc=$?
check "--out DIR//: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "--out DIR//: the summary line names DIR/slash/slash.png ($(cat "$T/e13"))" grep -q -- "-> $T/o13/slash/slash.png\$" "$T/e13"

# 14. a height made from width / the camera's aspect past the 32768 limit is an error at the width's
#     line and column (it had none: "job.yaml: height: ...")
sed "s/aspect: 1 }/aspect: 0.5 }/" "$root/scenes/cornell.yaml" >"$T/scenes/tall.yaml"
printf 'scene: ../scenes/tall.yaml\nwidth: 20000\nthreshold: 100\n' >"$T/jobs/tall.yaml"
"$WORKER" --out "$T/o14" "$T/jobs/tall.yaml" 2>"$T/e14"; rc=$?
check "height past the limit from the aspect: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "height past the limit from the aspect: file:line:col at width: ($(cat "$T/e14"))" \
    sh -c "[ \$(wc -l <'$T/e14') -eq 1 ] && grep -q '^$T/jobs/tall.yaml:2:8: width: .*40000 rows' '$T/e14'"
check "height past the limit from the aspect: nothing written" [ ! -e "$T/o14" ]

finish
