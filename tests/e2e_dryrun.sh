#!/bin/sh
# e2e_dryrun: `worker JOB --dry-run` prints samples, memory and CPU time (from a pilot of a few
# pixels) for a job, a compare job (with the reference-too-weak guard) and a suite, exits 0, and
# writes nothing anywhere; bad input is refused as a render would refuse it (issue 27).
. "$(dirname "$0")/lib.sh"
root=$(pwd)
mkdir -p "$T/w/st"
cd "$T/w" || exit 1
printf 'scene: %s/scenes/checker.yaml\nwidth: 16\nheight: 16\nsampler: uniform\nthreshold: 10\n' "$root" >job.yaml
cat >cmp.yaml <<EOT
name: cmp
scenes: [$root/scenes/checker.yaml]
width: 16
reference: { sampler: jitter, threshold: 10 }
seeds: [1, 2]
variants:
  - { sampler: uniform, threshold: 10 }
  - { sampler: jitter, threshold: 20 }
EOT
sed 's/reference: { sampler: jitter, threshold: 10 }/reference: { sampler: jitter, threshold: 2 }/' cmp.yaml >st/strong.yaml
printf 'name: suite\nstudies: [cmp.yaml, st/strong.yaml]\n' >suite.yaml
sed 's/^name: cmp/name: strong/' st/strong.yaml >st/s.yaml && mv st/s.yaml st/strong.yaml
ls -lAR >"$T/before"
"$WORKER" job.yaml --dry-run >"$T/job.out" 2>"$T/job.err"; rc=$?
check "job: exit 0 (got $rc: $(cat "$T/job.err"))" [ "$rc" -eq 0 ]
check "job: the samples, exact for a grid ($(cat "$T/job.out"))" grep -q "^  samples   25600 (100 per pixel)$" "$T/job.out"
check "job: memory" grep -Eq "^  memory    about [0-9.e+]+ MB \(framebuffer [0-9.e+-]+ MB \+ 2 processes x [0-9.e+]+ MB\)$" "$T/job.out"
check "job: CPU time from a pilot" grep -Eq "^  CPU time  about [0-9.]+ (ms|s|min|h) \([0-9.e+]+ ns per sample, from a pilot of 64 pixels\); wall about" "$T/job.out"
check "job: says nothing is written" grep -q "^job: dry run: nothing rendered, nothing written$" "$T/job.out"
"$WORKER" cmp.yaml --dry-run --processes 1 >"$T/cmp.out" 2>"$T/cmp.err"; rc=$?
check "compare: exit 0 (got $rc: $(cat "$T/cmp.err"))" [ "$rc" -eq 0 ]
check "compare: its images ($(cat "$T/cmp.out"))" grep -q "^  images    4 (1 scene x 2 variants x 1 point x 2 seeds): 64000 samples (25 to 100 per pixel)" "$T/cmp.out"
# the reference as rendered: two halves at t = 10 sqrt 2 (7x7 each), 98 per pixel, not t=10's 100
check "compare: the reference, as its two halves" grep -Eq "^  reference checker: 16x16 jitter t=10, light [a-z]+ t=[0-9.]+: 25088 samples \(98 per pixel: two halves at t=14.1421\)" "$T/cmp.out"
check "compare: the reference-too-weak guard, before rendering" grep -q "^  warning: checker: the reference would have 98 samples per pixel, fewer than 4x the densest point's 100" "$T/cmp.out"
check "compare: the total on 1 process" grep -q "^  CPU time  about .* in all (references .* of it, unless cached).* on 1 process$" "$T/cmp.out"
"$WORKER" --dry-run suite.yaml >"$T/suite.out" 2>"$T/suite.err"; rc=$?
check "suite: exit 0 (got $rc: $(cat "$T/suite.err"))" [ "$rc" -eq 0 ]
check "suite: both studies ($(cat "$T/suite.out"))" sh -c "grep -q '^ study cmp$' '$T/suite.out' && grep -q '^ study strong$' '$T/suite.out'"
check "suite: a strong reference is not warned about" [ "$(grep -c 'warning:' "$T/suite.out")" -eq 1 ]
# bad input: refused at its line:col, as a render would be
printf 'scene: %s/scenes/checker.yaml\nwidth: 1\nsampler: poisson\nthreshold: 1\npoisson_pool: 60000\n' "$root" >big.yaml
"$WORKER" big.yaml --dry-run >"$T/big.out" 2>"$T/big.err"; rc=$?
check "too big: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "too big: at poisson_pool's line:col ($(cat "$T/big.err"))" grep -q "^big.yaml:5:15: poisson_pool:" "$T/big.err"
# three textures naming one image (256x128, 96 KiB decoded): decoded once, and its pixels,
# shared by the forked renderers, counted once beside the processes' own memory
{
    printf 'camera: { lookfrom: [0, 0, 5], lookat: [0, 0, 0], vfov: 40 }\ntextures:\n'
    for i in 0 1 2; do printf '  t%s: { type: image, file: %s/scenes/textures/planet.png }\n' $i "$root"; done
    printf 'materials:\n  m: { type: lambertian, texture: t1 }\n  l: { type: light, emit: [4, 4, 4] }\nobjects:\n'
    printf '  - { type: sphere, center: [0, 0, 0], radius: 1, material: m }\n'
    printf '  - { type: sphere, center: [0, 5, 5], radius: 1, material: l }\n'
} >"$T/tex.yaml"
printf 'scene: %s\nwidth: 8\nthreshold: 50\n' "$T/tex.yaml" >tex.yaml
"$WORKER" tex.yaml --dry-run --processes 2 >"$T/tex.out" 2>"$T/tex.err"; rc=$?
check "textures: exit 0 (got $rc: $(cat "$T/tex.err"))" [ "$rc" -eq 0 ]
check "textures: one image's pixels, shared ($(cat "$T/tex.out"))" grep -Eq \
    "^  memory    about [0-9.e+]+ MB \(framebuffer [0-9.e+-]+ MB \+ textures 0.0938 MB, shared \+ 2 processes x [0-9.e+]+ MB\)$" \
    "$T/tex.out"
rm tex.yaml
# pixels costlier than the pilot's time (10000 stacked pyramids, 2500 samples of up to 50
# bounces: seconds a pixel): the pilot traces sets of at most 64 samples and stops at its budget
# (it once rendered whole pixels: 22 s for 100000 pyramids), so the dry run stays near half a
# second of CPU by its own account
{
    printf 'camera: { lookfrom: [20, 30, 20], lookat: [0, 40, 0], vfov: 60 }\nmaterials:\n'
    printf '  w: { type: lambertian, albedo: [0.7, 0.7, 0.7] }\n  l: { type: light, emit: [4, 4, 4] }\nobjects:\n'
    printf '  - &s {type: pyramid, apex: [0, 140, 0], base: [[-100, 0, -100], [140, 0, 0], [0, 0, 140]], material: w}\n'
    awk 'BEGIN { for (i = 1; i < 10000; i++) print "  - *s" }'
    printf '  - { type: sphere, center: [0, 400, 0], radius: 50, material: l }\n'
} >"$T/pyr.yaml"
printf 'scene: %s\nwidth: 32\nsampler: jitter\nthreshold: 2\nmax_depth: 50\n' "$T/pyr.yaml" >pyr.yaml
"$WORKER" pyr.yaml --dry-run >"$T/pyr.out" 2>"$T/pyr.err"; rc=$?
check "costly pixel: exit 0 (got $rc: $(cat "$T/pyr.err"))" [ "$rc" -eq 0 ]
check "costly pixel: the pilot kept to its budget ($(cat "$T/pyr.out"))" \
    python3 -c 'import re, sys; t = open(sys.argv[1]).read(); assert float(re.search(r"^  dry run   took ([0-9.e+-]+) s of CPU$", t, re.M).group(1)) < 2; assert re.search(r"^  CPU time  about [0-9.]+ (min|h) .*from a pilot of [0-9]+ pixels", t, re.M)' "$T/pyr.out"
rm pyr.yaml
# issue 36's new user: one seed, and sweep points that give one sample per pixel alike (thresholds
# 100 and 80), are warned about before rendering; under sampler_dims: all the light sampler is
# never asked, so neither the image line nor the reference's says "light jitter t=5"
cat >one.yaml <<EOT
name: one
scenes: [$root/scenes/checker.yaml]
width: 8
reference: { sampler: jitter, threshold: 10 }
seeds: [3]
sampler_dims: all
sweep: { threshold: [100, 80, 50] }
variants:
  - { sampler: jitter }
EOT
"$WORKER" one.yaml --dry-run >"$T/one.out" 2>&1; rc=$?
check "one seed: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "one seed: warned ($(cat "$T/one.out"))" grep -q "^  warning: one seed: no spread across seeds to judge a difference by" "$T/one.out"
check "thresholds 100 and 80: one sample per pixel alike, warned" \
    grep -q "^  warning: checker, jitter: sweep points threshold 100 and threshold 80 both give 1 sample per pixel" "$T/one.out"
check "thresholds 100 and 80: warned once, 50 not named" [ "$(grep -c "sweep points" "$T/one.out")" -eq 1 ]
check "sampler_dims: all: the reference's light points named as they are" \
    grep -q "^  reference checker: 8x8 jitter t=10, light points from the jitter sets (sampler_dims: all):" "$T/one.out"
check "sampler_dims: all: no light sampler claimed" sh -c "! grep -q 'light jitter' '$T/one.out'"
printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nsampler_dims: all\n' "$root" >dims.yaml
"$WORKER" dims.yaml --dry-run >"$T/dims.out" 2>&1
check "plain job, sampler_dims: all: the image line says where light points come from ($(head -n 2 "$T/dims.out"))" \
    grep -q "^  image     8x8, random t=5, light points from the random sets (sampler_dims: all) ->" "$T/dims.out"
rm one.yaml dims.yaml
"$WORKER" --queue "$T/q" --dry-run >/dev/null 2>"$T/q.err"; rc=$?
check "--dry-run with --queue: exit 2 (got $rc)" [ "$rc" -eq 2 ]
rm big.yaml
ls -lAR >"$T/after"
check "nothing written anywhere: $(diff "$T/before" "$T/after" | head -5)" cmp -s "$T/before" "$T/after"
check "no out/ folder" [ ! -e out ]
check "no queue folder" [ ! -e "$T/q" ]
cd "$root" || exit 1
# the render says what the dry run said: the same 98 per pixel in its verdict's warning
"$WORKER" --quiet --out "$T/real" "$T/w/cmp.yaml" 2>"$T/real.err"; rc=$?
check "compare rendered: exit 0 (got $rc: $(tail -n 1 "$T/real.err"))" [ "$rc" -eq 0 ]
check "compare rendered: the reference's 98 samples per pixel, as the dry run said" \
    grep -q "the reference has 98 samples per pixel" "$T/real/cmp/verdict.json"
finish
