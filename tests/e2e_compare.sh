#!/bin/sh
# End to end: a tiny compare job writes images, sidecars, summary.csv, chart.svg (valid XML) and a
# self-contained report.html that headless Chromium renders; a second run reuses the cached
# references and says so; at equal samples on the checker scene jitter and poisson beat random;
# the shipped compare jobs run (shrunk); bad compare jobs exit 2 with file:line:col before
# rendering anything.
. tests/lib.sh
root=$(pwd)
variants='
variants:
  - { sampler: poisson, light_sampler: poisson }
  - { sampler: jitter,  light_sampler: jitter }
  - { sampler: uniform, light_sampler: uniform }
  - { sampler: random,  light_sampler: random }
  - { sampler: poisson, light_sampler: poisson, poisson_pool: 16 }'

# 1. two scenes x 5 variants x 2 thresholds x 2 seeds = 40 tiny images
cp scenes/checker.yaml "$T/board.yaml"
cat >"$T/cmp.yaml" <<EOF
name: cmp
scenes: [$root/scenes/checker.yaml, $T/board.yaml]
width: 32
height: 24
reference: { sampler: jitter, threshold: 5 }
seeds: [1, 2]
sweep: { threshold: [50, 25] }
$variants
EOF
"$WORKER" --out "$T/out" "$T/cmp.yaml" 2>"$T/run1.err"; rc=$?
check "compare job exits 0 (got $rc: $(tail -n 1 "$T/run1.err"))" [ "$rc" -eq 0 ]
cdir=$T/out/cmp
check "40 images" [ "$(ls "$cdir"/*.png 2>/dev/null | wc -l)" -eq 40 ]
check "40 sidecars" [ "$(ls "$cdir"/*.json 2>/dev/null | grep -vc '/verdict\.json$')" -eq 40 ]
for f in checker-jitter-t25-s2 checker-poisson-t50-s1 board-uniform-t25-s1 board-poisson-pool16-t50-s2; do
    check "image and sidecar $f" test -s "$cdir/$f.png" -a -s "$cdir/$f.json"
done
check "sidecar scores against the cached reference" grep -q '"reference": ".*/.cache/ref-checker-' "$cdir/checker-jitter-t25-s2.json"
check "sidecar has relmse" grep -q '"relmse": [0-9]' "$cdir/checker-jitter-t25-s2.json"
check "sidecar threshold 25" grep -q '"threshold": 25,' "$cdir/checker-jitter-t25-s2.json"
check "sidecar seed 2" grep -q '"seed": 2,' "$cdir/checker-jitter-t25-s2.json"
check "one cached reference per scene, a float image" [ "$(ls "$T"/out/.cache/ref-*[0-9a-f][0-9a-f].exr 2>/dev/null | wc -l)" -eq 2 ]
check "each the mean of two cached halves" [ "$(ls "$T"/out/.cache/ref-*-[ab].exr 2>/dev/null | wc -l)" -eq 4 ]
check "no 8-bit cached reference" [ "$(ls "$T"/out/.cache/ref-*.png 2>/dev/null | wc -l)" -eq 0 ]
check "every render keeps its float image beside its PNG" \
    eval '[ "$(ls "$cdir"/*.exr | wc -l)" -eq 40 ] && [ -s "$cdir/checker-jitter-t25-s2.exr" ]'
check "sidecar: error in linear radiance" grep -q '"domain": "linear"' "$cdir/checker-jitter-t25-s2.json"
check "first run rendered both references" grep -q "references: 2 rendered, 0 reused from cache" "$T/run1.err"
check "the summary line counts the combinations" grep -q "cmp: 40 images (2 scenes x 5 variants x 2 sweep points x 2 seeds)" "$T/run1.err"

# summary.csv: a header and one row of 40 fields per image (the render's settings, render_spec's
# rows, around the figures), with its metrics in linear radiance
# (mse, rmse, relmse, relmse_robust, psnr, domain) and the 8-bit display figures beside them
csv=$cdir/summary.csv
check "summary.csv header" [ "$(head -n 1 "$csv")" = "scene,variant,threshold,light_threshold,seed,samples_per_pixel_mean,wall_s,cpu_s,sampler_share,mse,rmse,relmse,relmse_robust,psnr,domain,rmse_8bit,relmse_8bit,error_lowfreq,flip,camera_samples,path_segments,shadow_rays,pixel_points,light_points,padded_points,pixel_sets,light_sets,padded_sets,width,height,sampler,light_sampler,light_sampling,integrator,sampler_dims,russian_roulette,poisson_pool,poisson_domain,max_depth,image" ]
check "summary.csv has 40 rows" [ "$(tail -n +2 "$csv" | wc -l)" -eq 40 ]
check "every row has 40 fields, a flip in (0, 1), a relmse, a robust one no larger, linear, and 8-bit figures" \
    [ "$(awk -F, 'NR > 1 && NF == 40 && $19 + 0 > 0 && $19 + 0 < 1 && $12 + 0 > 0 && $13 <= $12 && $15 == "linear" && $17 + 0 > 0' "$csv" | wc -l)" -eq 40 ]
# error_lowfreq (how the error looks: its low-frequency share over white noise's) is a positive
# number for every 32x24 image, near 1 for noise (docs/compare.md)
check "every row's error_lowfreq is a positive number" \
    [ "$(awk -F, 'NR > 1 && $18 ~ /^[0-9]+\.[0-9]+$/ && $18 + 0 > 0 && $18 + 0 < 20' "$csv" | wc -l)" -eq 40 ]
# the row's relmse is its sidecar's and worker diff's of the float images (to the CSV's 6 digits)
row=$(grep ',checker-jitter-t25-s2.png$' "$csv")
ref=$(ls "$T"/out/.cache/ref-checker-*[0-9a-f][0-9a-f].exr)
drel=$("$WORKER" diff "$ref" "$cdir/checker-jitter-t25-s2.exr" | awk '$1 == "relmse" {print $2}')
srel=$(sed -n 's/.*"relmse": \([0-9.e+-]*\).*/\1/p' "$cdir/checker-jitter-t25-s2.json")
check "summary.csv relmse = the sidecar's = worker diff's on the EXRs ($row; $srel; $drel)" \
    awk -v a="$(echo "$row" | cut -d, -f12)" -v b="$srel" -v c="$drel" \
    'BEGIN { exit !(b > 0 && (a - b) ^ 2 <= (1e-5 * b) ^ 2 && (c - b) ^ 2 <= (1e-8 * b) ^ 2) }'
check "uniform t=25 has 16 samples per pixel" grep -q '^checker,uniform,25,5,1,16.00,' "$csv"
check "rows name their images" grep -q ',board-poisson-pool16-t50-s2.png$' "$csv"
# Every row's times and sampler share are its sidecar's to 5 significant digits: these tiny images
# take about a millisecond, so a fixed 4 decimals would round them by up to 10% or to 0.
sidecar_matches() { # every row against the first "key": of its sidecar, relative 1e-5
    mism=0
    while IFS=, read -r _ _ _ _ _ _ wall cpu share _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ _ img; do
        side="$cdir/${img%.png}.json"
        for kv in "wall_s $wall" "cpu_s $cpu" "sampling_share $share"; do
            set -- $kv
            want=$(sed -n "s/.*\"$1\": \([0-9.e+-]*\).*/\1/p" "$side" | head -n 1)
            awk -v a="$2" -v b="$want" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(b > 0 && d <= 1e-5 * b) }' ||
                { echo "$img: $1 $2 in summary.csv, $want in its sidecar" >&2; mism=1; }
        done
    done <<EOF
$(tail -n +2 "$csv")
EOF
    [ "$mism" -eq 0 ]
}
check "summary.csv times match the sidecars" sidecar_matches

# chart.svg: valid XML, 2 panels per scene, one line per variant, guides, units
svg=$cdir/chart.svg
if command -v python3 >/dev/null 2>&1; then
    check "chart.svg parses as XML (python3)" python3 -c "import sys, xml.etree.ElementTree as E; E.parse(sys.argv[1])" "$svg"
elif command -v xmllint >/dev/null 2>&1; then
    check "chart.svg parses as XML (xmllint)" xmllint --noout "$svg"
else
    no "no XML parser (python3 or xmllint): ci/run installs python3"
fi
check "chart: 20 lines (2 scenes x 2 panels x 5 variants)" [ "$(grep -c '<polyline' "$svg")" -eq 20 ]
check "chart: 4 panels" [ "$(grep -c 'error against' "$svg")" -eq 4 ]
check "chart: time axis with unit" grep -q 'CPU time per image (s, log)' "$svg"
check "chart: samples axis" grep -q 'samples per pixel (mean, log)' "$svg"
check "chart: relMSE axis" grep -q 'relMSE (eps 0.01, log)' "$svg"
check "chart: dotted guide slopes" grep -q 'stroke-dasharray' "$svg"
check "chart: legend names the pool variant" grep -q '>poisson-pool16<' "$svg"
check "chart: whiskers" grep -q '<path d="M' "$svg"

# report.html: self-contained, every part present
html=$cdir/report.html
check "report: html5" sh -c "head -n 1 '$html' | grep -q '<!DOCTYPE html>'"
check "report: inline chart" grep -q '<svg xmlns' "$html"
check "report: the chart shrinks to the page's width (a long label widens its legend)" \
    grep -q 'svg{max-width:100%;height:auto}' "$html"
check "report: images as data URIs" [ "$(grep -o 'src="data:image/png;base64,' "$html" | wc -l)" -ge 40 ]
check "report: nothing from the network" sh -c "! grep -Eqi '(src|href)=\"(https?:)?//|url\\(|@import' '$html'"
check "report: sample counts side by side" grep -q '</b> t=25: 16 spp' "$html"
check "report: zoomed crops (32x24 images: 24-pixel windows at 7x)" grep -q '7x nearest-neighbour crops' "$html"
check "report: error maps" grep -q 'Error maps at' "$html"
# Images a person can judge: every render at an integer zoom >= 2 (32 px wide: 8x), pixelated,
# the reference at the same size; every seed's render on the page, behind a seed button
check "report: renders at 8x, 256x192" [ "$(grep -c '<figure class="sd" data-seed="[0-9]" data-slot="g[0-9]*v[0-9]*"[^>]*><img class="z" data-ab="ref[01]" src="data:image/png;base64,[^"]*" width="256" height="192"' "$html")" -eq 40 ]
check "report: the references at the renders' size" [ "$(grep -c '<img class="z" id="ref[01]" src="data:image/png;base64,[^"]*" width="256" height="192"' "$html")" -eq 2 ]
check "report: pixelated" grep -q 'img.z{image-rendering:pixelated' "$html"
missing=$(tail -n +2 "$csv" | awk -F, '{print $NF}' | while read -r f; do grep -q "alt=\"[^\"]* $f\"" "$html" || echo "$f"; done)
check "report: every seed's render on the page (missing: $missing)" [ -z "$missing" ]
check "report: a seed button per seed and scene" [ "$(grep -o '<button data-seed="[01]"' "$html" | wc -l)" -eq 4 ]
check "report: seed index 1 hidden until chosen" \
    [ "$(grep -c 'data-seed="1" data-slot="[^"]*" hidden>' "$html")" -eq "$(grep -c 'data-seed="1" data-slot=' "$html")" ]
check "report: seed index 0 shown" sh -c "! grep -q 'data-seed=\"0\" data-slot=\"[^\"]*\" hidden>' '$html'"
check "report: the A/B toggle, explained" sh -c "grep -q '<button class=\"ab\">' '$html' && grep -q 'Hold R, or hold the A/B button' '$html'"
check "report: crops swap to the reference's crop" grep -q 'data-ab="ref0c[0-9]"' "$html"
check "report: click to enlarge, the script inline" sh -c "grep -q 'Click an image to enlarge it' '$html' && grep -q '<script>(function(){' '$html'"
check "report: the error maps' scale drawn, with its numbers" \
    sh -c "grep -q '<div class=\"cbar\"><img src=\"data:image/png;base64,' '$html' && grep -q 'from -4 (black) to 2 (pale yellow)' '$html' && grep -q '>1e-2<br>10%<' '$html'"
check "report: the error maps in linear radiance" grep -q 'Error maps at .*in linear radiance (the float images)' "$html"
check "report: no 8-bit |diff| maps" sh -c "! grep -q 'image - reference| x' '$html'"
check "report: one stability line per variant and scene" [ "$(grep -c '^<li><b>' "$html")" -eq 10 ]
check "report: stability names how well the seeds pin the error down" grep -q 'relMSE over 2 seeds known within a factor' "$html"
check "report: opens with the verdict" sh -c "sed -n '/<h1>/,\$p' '$html' | grep -m1 -o '<h2>[^<]*' | grep -qx '<h2>Verdict'"
check "report: a verdict per scene" [ "$(grep -c '<h3>cmp / ' "$html")" -eq 2 ]
check "report: the rule is stated" grep -q 'How it is decided' "$html"
check "verdict.json beside the report" python3 -c "
import json, sys
d = json.load(open('$cdir/verdict.json'))
s = d['studies'][0]
assert d['job'] == 'cmp' and s['study'] == 'cmp' and [x['scene'] for x in s['scenes']] == ['checker', 'board']
for x in s['scenes']:
    for k in ('equal_samples', 'equal_cpu_time', 'slopes'):
        assert x[k]['status'] in ('clear', 'tie', 'inconclusive') and len(x[k]['ranking']) == 5, x[k]
        assert sorted(e['rank'] for e in x[k]['ranking'])[0] == 1, x[k]
    assert isinstance(x['failures'], list) and isinstance(x['warnings'], list) and x['sentences']
"
# a scene's sidecars gone: only that scene's verdict says what it skipped, with its own count
cp -r "$cdir" "$T/nosc"
rm "$T"/nosc/board-*.json
n_board=$(ls "$cdir"/board-*.json | wc -l)
"$WORKER" verdict "$T/nosc" --json >"$T/nosc.json" 2>/dev/null
check "sidecars of one scene gone: its warning alone, its count ($n_board)" python3 -c "
import json
s = {x['scene']: ' '.join(x['warnings']) for x in json.load(open('$T/nosc.json'))['studies'][0]['scenes']}
assert '($n_board sidecars missing)' in s['board'], s['board']
assert 'sidecars missing' not in s['checker'], s['checker']
"
# how the error looks: error_lowfreq per variant in verdict.json, a plot per study in the report,
# and the same figures when the folder's summary.csv is read back (worker verdict)
"$WORKER" verdict "$cdir" --json >"$T/look.json" 2>/dev/null
check "verdict.json: error_lowfreq per variant, the bluest at equal relMSE, and again from summary.csv" python3 -c "
import json, math
d, again = (json.load(open(p)) for p in ('$cdir/verdict.json', '$T/look.json'))
for s, t in zip(d['studies'][0]['scenes'], again['studies'][0]['scenes']):
    x = s['error_look']
    assert x['at_samples_per_pixel'] > 0 and len(x['variants']) == 5, x
    assert all(v['error_lowfreq'] > 0 and v['standard_error'] >= 0 for v in x['variants']), x
    assert x['bluest']['status'] in ('clear', 'tie', 'inconclusive') and x['bluest']['ranking'], x
    for v, w in zip(x['variants'], t['error_look']['variants']):
        assert math.isclose(v['error_lowfreq'], w['error_lowfreq'], rel_tol=1e-3), (v, w)
"
check "report: the study's error_lowfreq plot" grep -q 'checker: how the error looks' "$html"
check "report: the table has every image" [ "$(grep -c '^<tr><td class="l">' "$html")" -eq 40 ]
# Links: relative, and each resolves from the report's folder (the page may be opened anywhere)
grep -o 'href="[^"]*"' "$html" | sed 's/^href="//; s/"$//' >"$T/links"
check "report: links to summary.csv and chart.svg" sh -c "grep -qx summary.csv '$T/links' && grep -qx chart.svg '$T/links'"
check "report: every image and sidecar linked from the table" \
    [ "$(grep -c '\.png$' "$T/links")" -eq 40 -a "$(grep -v '^verdict\.json$' "$T/links" | grep -c '\.json$')" -eq 40 ]
unresolved=$(while read -r l; do [ -e "$cdir/$l" ] || echo "$l"; done <"$T/links")
check "report: every link resolves (unresolved: $unresolved)" [ -z "$unresolved" ]

# 1b. without a reference: images and table, no metrics; with an image file as the reference
printf 'name: noref\nscenes: [checker]\nwidth: 16\nseeds: [1, 2]\nsweep: { threshold: [50, 25] }\nvariants:\n  - { sampler: jitter }\n  - { sampler: random }\n' >"$T/noref.yaml"
"$WORKER" --quiet --out "$T/out" "$T/noref.yaml" 2>"$T/noref.err"; rc=$?
check "no reference: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "no reference: 8 rows without metrics" [ "$(awk -F, 'NR > 1 && $12 == ""' "$T/out/noref/summary.csv" | wc -l)" -eq 8 ]
check "no reference: the chart says so" grep -q 'no reference given' "$T/out/noref/chart.svg"
check "no reference: the summary line says so" grep -q 'no reference' "$T/noref.err"
cp "$T/out/noref/checker-jitter-t25-s1.png" "$T/given.png"
printf 'name: given\nscene: checker\nwidth: 16\nreference: given.png\nvariants:\n  - { sampler: random, threshold: 50 }\n' >"$T/given.yaml"
"$WORKER" --quiet --out "$T/out" "$T/given.yaml" 2>/dev/null; rc=$?
check "reference image file: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "reference image file: scored" [ "$(awk -F, 'NR == 2 && $12 > 0' "$T/out/given/summary.csv" | wc -l)" -eq 1 ]
check "reference image file: its error maps on 8-bit display values, and say so" \
    grep -q 'Error maps at .*on 8-bit display values v / 255' "$T/out/given/report.html"
# a light_threshold sweep leaves samples per pixel alone: efficiency is read at the sweep's last
# point, and the report says so instead of "densest"
printf 'name: lts\nscene: checker\nwidth: 8\nreference: { sampler: jitter, threshold: 20 }\nsweep: { light_threshold: [50, 25] }\nvariants:\n  - { sampler: jitter, threshold: 50 }\n' >"$T/lts.yaml"
"$WORKER" --quiet --out "$T/out" "$T/lts.yaml" 2>/dev/null; rc=$?
check "light_threshold sweep: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "light_threshold sweep: no slope to rank by" python3 -c "
import json
x = json.load(open('$T/out/lts/verdict.json'))['studies'][0]['scenes'][0]
assert x['slopes']['ranking'] == [] and x['equal_samples']['ranking'][0]['variant'] == 'jitter-t50', x"
# a long sweep: the stability line names every point and ends with its note, however long
printf 'name: ltl\nscene: checker\nwidth: 4\nreference: { sampler: jitter, threshold: 50 }\nseeds: [1, 2]\nsweep: { light_threshold: [90, 85, 80, 75, 70, 65, 60, 55, 50, 45, 40, 35, 30, 25, 20, 15, 12, 11] }\nvariants:\n  - { sampler: jitter, threshold: 50 }\n' >"$T/ltl.yaml"
"$WORKER" --quiet --out "$T/out" "$T/ltl.yaml" 2>/dev/null; rc=$?
check "18-point sweep: exit 0 (got $rc)" [ "$rc" -eq 0 ]
check "18-point sweep: the stability line is whole" \
    grep -q '% at light_threshold 11[^<]*own relMSE, [0-9.e-]*, taken out)</li>' \
    "$T/out/ltl/report.html"
# a scene file whose name holds a comma and a quote: its CSV fields are quoted (RFC 4180)
cp scenes/checker.yaml "$T/chk,e\"r.yaml"
printf 'name: comma\nscenes: ["chk,e\\"r.yaml"]\nwidth: 8\nvariants:\n  - { sampler: jitter, threshold: 50 }\n' >"$T/comma.yaml"
"$WORKER" --quiet --out "$T/out" "$T/comma.yaml" 2>"$T/comma.err"; rc=$?
check "comma in a scene name: exit 0 (got $rc: $(cat "$T/comma.err"))" [ "$rc" -eq 0 ]
check "comma in a scene name: fields quoted" grep -q '^"chk,e""r",jitter-t50,50,5,1,4.00,.*,"chk,e""r-jitter-t50-t50-s1.png"$' "$T/out/comma/summary.csv"
check "comma in a scene name: the report's link is percent-encoded" \
    grep -q 'href="chk%2Ce%22r-jitter-t50-t50-s1.png"' "$T/out/comma/report.html"

# 2. the second run reuses both references, says so, and leaves them untouched
before=$(ls -li --time-style=full-iso "$T"/out/.cache/ref-*.exr)
"$WORKER" --out "$T/out" "$T/cmp.yaml" 2>"$T/run2.err"; rc=$?
check "second run exits 0" [ "$rc" -eq 0 ]
check "second run summary: 0 rendered, 2 reused" grep -q "references: 0 rendered, 2 reused from cache (saving [0-9.]* s)" "$T/run2.err"
check "not a terminal: only the summary line (and the verdict's warnings)" [ "$(grep -vc ': warning: ' "$T/run2.err")" -eq 1 ]
check "cached references not rewritten" [ "$before" = "$(ls -li --time-style=full-iso "$T"/out/.cache/ref-*.exr)" ]
# a changed scene file is a new cache key: only its reference renders again
echo "# changed" >>"$T/board.yaml"
"$WORKER" --quiet --out "$T/out" "$T/cmp.yaml" 2>"$T/run3.err"
check "changed scene: 1 rendered, 1 reused" grep -q "references: 1 rendered, 1 reused from cache" "$T/run3.err"
check "--quiet: only the summary line (and the verdict's warnings)" [ "$(grep -vc ': warning: ' "$T/run3.err")" -eq 1 ]
# a cached half that is not the one its record names (another scene's put at its name, a PFM
# renamed .exr) is rendered again, to the same bytes, and the reference with it
ref=$(sed -n 's/.*"reference": "\(.*\)\.exr".*/\1/p' "$cdir/checker-jitter-t25-s2.json")
ha=$ref-a.exr hb=$ref-b.exr
good=$(cksum <"$ha")
cp "$(ls -t "$T"/out/.cache/ref-board-*-a.exr | head -n 1)" "$ha"
"$WORKER" --out "$T/out" "$T/cmp.yaml" 2>"$T/run4.err"
check "another scene's half at its name: rendered again" grep -q "references: 1 rendered, 1 reused from cache" "$T/run4.err"
check "... to the same bytes" [ "$(cksum <"$ha")" = "$good" ]
good=$(cksum <"$hb")
printf 'PF\n1 1\n-1.0\n' >"$hb" && head -c 12 /dev/zero >>"$hb"
"$WORKER" --quiet --out "$T/out" "$T/cmp.yaml" 2>"$T/run5.err"
check "a PFM renamed .exr: rendered again" grep -q "references: 1 rendered, 1 reused from cache" "$T/run5.err"
check "... to the same bytes" [ "$(cksum <"$hb")" = "$good" ]

# 3. progress: one line per combination on a terminal (script(1) gives it one)
if command -v script >/dev/null 2>&1; then
    script -qec "'$WORKER' --out '$T/out' '$T/cmp.yaml'" /dev/null >"$T/tty.out" 2>&1
    check "progress: a line per combination" [ "$(grep -c '^\[[ 0-9]*/40\] .* spp, .* ETA' "$T/tty.out")" -eq 40 ]
    check "progress: names scene, variant, threshold, seed" grep -q '^\[[ 0-9]*/40\] checker poisson t=50 seed 1: ' "$T/tty.out"
    check "progress: seed-major, shuffled: the first image is a first seed's" grep -q '\[ 1/40\] [a-z-]* [a-z0-9-]* t=[0-9.]* seed 1: ' "$T/tty.out"
    check "progress: says each reference was reused" [ "$(grep -c 'reference reused from cache .*(it took' "$T/tty.out")" -eq 2 ]
    # a reference rendered on a terminal: its progress names the scene and the half, not ".cache"
    sed 's/^name: cmp$/name: cmpref/; s/^seeds: .*/seeds: [1]/' "$T/cmp.yaml" >"$T/cmpref.yaml"
    script -qec "'$WORKER' --out '$T/outref' '$T/cmpref.yaml'" /dev/null >"$T/ttyref.out" 2>&1
    check "progress: a reference's half is named by its scene" grep -q 'checker reference a' "$T/ttyref.out"
    check "progress: ... never as .cache" sh -c "! grep -q '\.cache: ' '$T/ttyref.out'"
else
    echo "note: script(1) missing, progress lines not checked"
fi

# 4. the report in headless Chromium: the screenshot is not blank
chromium=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chromium" ] && [ -z "${NO_INSTALL:-}" ] && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "installing chromium (Debian package) for the screenshot test"
    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium; } >"$T/apt.log" 2>&1
    chromium=$(command -v chromium || true)
fi
if [ -n "$chromium" ]; then
    mkdir -p "$T/profile"
    timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
        --disable-background-networking --disable-component-update --disable-sync \
        --user-data-dir="$T/profile" --screenshot="$T/shot.png" --window-size=1200,2000 \
        "file://$html" >"$T/chromium.log" 2>&1
    check "chromium wrote a screenshot" [ -s "$T/shot.png" ]
    set -- $(od -An -tu1 -j16 -N8 "$T/shot.png" 2>/dev/null) 0 0 0 0 0 0 0 0
    w=$(( ($1 << 24) + ($2 << 16) + ($3 << 8) + $4 )); h=$(( ($5 << 24) + ($6 << 16) + ($7 << 8) + $8 ))
    check "screenshot is 1200x2000 (got ${w}x$h)" test "$w" -eq 1200 -a "$h" -eq 2000
    # Blank would be one colour: score the screenshot against all-white and all-black images
    # with `worker diff` (our PNG decoder); from the two MSEs follow its mean and variance.
    for c in white black; do
        v='\377'; [ $c = black ] && v='\000'
        { printf 'P6\n%d %d\n255\n' "$w" "$h"; head -c $((w * h * 3)) /dev/zero | tr '\000' "$v"; } >"$T/$c.ppm"
        "$WORKER" diff "$T/$c.ppm" "$T/shot.png" | awk '$1 == "mse" {print $2}' >"$T/$c.mse"
    done
    var=$(awk -v w="$(cat "$T/white.mse")" -v b="$(cat "$T/black.mse")" 'BEGIN { m = (1 + b - w) / 2; printf "%.5f", b - m * m }')
    echo "screenshot: pixel variance $var (a blank page: 0)"
    check "screenshot is not blank (variance $var > 0.01)" awk -v v="$var" 'BEGIN { exit !(v > 0.01) }'
    # The page's script at work: seed 2's button shows seed 2's 20 figures of the first scene (10
    # renders, 5 crops, 5 maps) and hides seed 1's; holding R puts the reference in each of its 20
    # renders' place and letting go restores them; a click enlarges an image by a whole factor.
    cat >"$T/drive.js" <<'EOF'
addEventListener('load', function () {
    var s = document.querySelector('section.scene');
    s.querySelector('button[data-seed="1"]').click();
    dispatchEvent(new KeyboardEvent('keydown', {key: 'r'}));
    var vis = function (k) { return s.querySelectorAll('figure[data-seed="' + k + '"]:not([hidden])').length; };
    var r = document.getElementById('ref0').src, sw = 0, all = 0, back = 0;
    s.querySelectorAll('img[data-ab="ref0"]').forEach(function (i) { all++; if (i.src === r) sw++; });
    dispatchEvent(new KeyboardEvent('keyup', {key: 'r'}));
    s.querySelectorAll('img[data-ab="ref0"]').forEach(function (i) { if (i.src !== r) back++; });
    var im = s.querySelector('figure[data-seed="1"] img.z');
    im.click();
    var o = document.querySelector('#ov img'), k = o.width / im.naturalWidth;
    document.title = 'seeds ' + vis(0) + ' ' + vis(1) + ' swapped ' + sw + '/' + all + ' back ' + back +
        ' enlarged ' + (k === Math.floor(k) && k > 8 ? 'whole' : k);
});
EOF
    { sed 's#</body></html>##' "$html"; printf '<script>'; cat "$T/drive.js"; printf '</script></body></html>\n'; } >"$cdir/drive.html"
    timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
        --disable-background-networking --disable-component-update --disable-sync \
        --user-data-dir="$T/profile" --window-size=1200,2000 --dump-dom "file://$cdir/drive.html" >"$T/dom.html" 2>"$T/chromium.log"
    rm -f "$cdir/drive.html"
    got=$(sed -n 's/.*<title>\(seeds [^<]*\)<\/title>.*/\1/p' "$T/dom.html")
    check "the page's script: seeds, A/B and enlarging work (got: $got)" \
        [ "$got" = "seeds 0 20 swapped 20/20 back 20 enlarged whole" ]
else
    echo "note: chromium missing and not installed (not root, no apt-get, or NO_INSTALL set): screenshot not checked"
fi

# 5. at equal samples on checker, jitter and poisson below random. The light sampler is random
# for all three, so only the pixel sampler differs; poisson t=3.92 gives ~400 samples like t=5 (a toroidal set holds about 6150 / t^2).
cat >"$T/order.yaml" <<EOF
name: order
scenes: [$root/scenes/checker.yaml]
width: 64
height: 48
light_sampler: random
reference: { sampler: jitter, threshold: 2 }
seeds: [1, 2, 3, 4, 5]
variants:
  - { sampler: jitter, threshold: 5 }
  - { sampler: random, threshold: 5 }
  - { sampler: poisson, threshold: 3.92 }
EOF
"$WORKER" --quiet --out "$T/out" "$T/order.yaml" 2>/dev/null
ocsv=$T/out/order/summary.csv
check "poisson t=3.92 has equal samples (400 +- 2%)" awk -F, '$2 == "poisson-t3.92" && ($6 < 392 || $6 > 408) { bad = 1 } END { exit bad }' "$ocsv"
# The margin is measured over the seeds: the difference of the mean relMSEs in units of its
# standard error across the 5 seeds must pass 2, and the ratio 1.05 (measured: jitter 1.22x
# below random at z = 4.1, poisson 1.16x at z = 3.6).
order() { # order VARIANT: VARIANT's mean relMSE is below random's by > 2 standard errors and 5%
    awk -F, -v a="$1" '
        $2 == a { na++; sa += $12; qa += $12 * $12 }
        $2 == "random-t5" { nr++; sr += $12; qr += $12 * $12 }
        END {
            ma = sa / na; mr = sr / nr
            va = (qa - na * ma * ma) / (na - 1); vr = (qr - nr * mr * mr) / (nr - 1)
            se = sqrt(va / na + vr / nr); z = (mr - ma) / se
            printf "%s: mean relMSE %.4g vs random %.4g: %.2fx lower, z = %.1f\n", a, ma, mr, mr / ma, z
            exit !(na == 5 && nr == 5 && z > 2 && mr / ma > 1.05)
        }' "$ocsv"
}
check "jitter below random at equal samples" order jitter-t5
check "poisson below random at equal samples" order poisson-t3.92
# The error maps of these converged images (400 spp) still show their error: on the fixed log
# scale a relMSE term of 1e-3 is dark purple, not black. Seed 1's map of each variant: the
# renders' size, and its RMS brightness from `worker diff` against an all-black image.
ohtml=$T/out/order/report.html
check "error maps: the scale is stated" grep -q 'Error maps at .*coloured by its log10 on one fixed scale' "$ohtml"
grep 'data-seed="0" data-slot="m0v[0-9]*"' "$ohtml" | # each figure's first image (its FLIP map follows)
    awk 'match($0, /base64,[^"]*/) { print substr($0, RSTART + 7, RLENGTH - 7) }' >"$T/maps.b64"
check "error maps: three maps" [ "$(wc -l <"$T/maps.b64")" -eq 3 ]
dark=0; n=0; sizes=""
while read -r b64; do
    n=$((n + 1))
    echo "$b64" | base64 -d >"$T/map$n.png"
    set -- $(od -An -tu1 -j16 -N8 "$T/map$n.png") 0 0 0 0 0 0 0 0
    w=$(( ($1 << 24) + ($2 << 16) + ($3 << 8) + $4 )); h=$(( ($5 << 24) + ($6 << 16) + ($7 << 8) + $8 ))
    sizes="$sizes ${w}x$h"
    { printf 'P6\n%d %d\n255\n' "$w" "$h"; head -c $((w * h * 3)) /dev/zero; } >"$T/mapblack.ppm"
    rms=$("$WORKER" diff "$T/mapblack.ppm" "$T/map$n.png" | awk '$1 == "rmse" {print $2}')
    echo "error map $n: RMS brightness $rms"
    awk -v r="$rms" 'BEGIN { exit !(r > 0.1) }' || dark=$((dark + 1))
done <"$T/maps.b64"
check "error maps: the renders' size (got$sizes)" [ "$sizes" = " 64x48 64x48 64x48" ]
check "error maps: none nearly black (RMS brightness > 0.1)" [ "$n" -eq 3 -a "$dark" -eq 0 ]
check "error maps: shown at the renders' zoom (64 px: 4x)" \
    [ "$(grep -c 'data-slot="m0v[0-9]*"[^>]*><img class="z" src="data:image/png;base64,[^"]*" width="256" height="192"' "$ohtml")" -eq 15 ]

# 6. the shipped compare jobs run, shrunk to 8x8 pixels, two thresholds and a coarse reference
shrink() { # shrink FILE: FILE at 8x8 pixels, thresholds 50 and 25, a reference at threshold 20
    sed -e 's/^width:.*/width: 8/' -e 's/^height:.*/height: 8/' \
        -e 's/threshold: \[[^]]*\]/threshold: [50, 25]/g' -e 's/threshold: [0-9.]* }/threshold: 20 }/' "$1"
}
for j in jobs/seed-experiment.yaml; do
    n=$(basename "$j" .yaml)
    shrink "$j" | sed "s/^name:.*/name: $n/" >"$T/jobs-$n.yaml"
    "$WORKER" --quiet --out "$T/shipped" "$T/jobs-$n.yaml" 2>"$T/$n.err"; rc=$? # bare scene names: ./scenes
    images=$(awk -F, 'NR > 1' "$T/shipped/$n/summary.csv" 2>/dev/null | wc -l)
    variants=$(grep -c '^  - {' "$j"); scenes=$(sed -n 's/^scenes: \[\(.*\)\]/\1/p' "$j" | tr ',' '\n' | wc -l)
    seeds=$(sed -n 's/^seeds: \[\(.*\)\]/\1/p' "$j" | tr ',' '\n' | wc -l)
    check "$j runs (exit $rc: $(head -n 1 "$T/$n.err"))" [ "$rc" -eq 0 ]
    check "$j: $scenes scenes x $variants variants x 2 thresholds x $seeds seeds (got $images)" \
        [ "$images" -eq $((scenes * variants * 2 * seeds)) ]
    check "$j: report written" [ -s "$T/shipped/$n/report.html" ]
done
# the headline job is a suite of the shipped studies (each of which e2e_studies runs alone): it
# runs with them shrunk alike, into a folder per study, with the suite's verdict on top
check "jobs/compare.yaml: a suite of the five shipped studies" grep -qx \
    'studies: \[studies/seed-question.yaml, studies/soft-shadows.yaml, studies/aliasing.yaml, studies/error-look.yaml, studies/cost.yaml\]' jobs/compare.yaml
mkdir -p "$T/suite/studies"
cp jobs/compare.yaml "$T/suite/compare.yaml"
for f in jobs/studies/*.yaml; do shrink "$f" >"$T/suite/studies/$(basename "$f")"; done
"$WORKER" --quiet --out "$T/shipped" "$T/suite/compare.yaml" 2>"$T/suite.err"; rc=$? # bare scene names: ./scenes
check "jobs/compare.yaml runs, its studies shrunk (exit $rc: $(tail -n 1 "$T/suite.err"))" [ "$rc" -eq 0 ]
check "jobs/compare.yaml: each study's report, the suite's report and verdict" sh -c \
    "[ \$(ls '$T'/shipped/compare/*/report.html | wc -l) -eq 5 ] && [ -s '$T/shipped/compare/report.html' ] && [ -s '$T/shipped/compare/verdict.json' ]"
check "jobs/compare.yaml's studies: checker and cornell" grep -q '^scenes: \[checker, cornell\]' jobs/studies/seed-question.yaml

# 7. bad compare jobs: exit 2, file:line:col, nothing rendered
bad() { # bad NAME EXPECTED-REGEX (job in $T/NAME.yaml)
    rm -rf "$T/badout"
    "$WORKER" --out "$T/badout" "$T/$1.yaml" 2>"$T/$1.err"; rc=$?
    check "$1: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "$1: '$2' (got: $(head -n 1 "$T/$1.err"))" grep -Eq "^$T/$1.yaml:$2" "$T/$1.err"
    check "$1: nothing written" [ ! -e "$T/badout" ]
}
printf 'scenes: [checker]\nvariants:\n  - { sampler: jitter }\n  - { sampler: random, treshold: 5 }\n' >"$T/badkey.yaml"
bad badkey '4:24: treshold: unknown key in variant \(did you mean "threshold"\?\)'
printf 'scenes: [checker]\nsweep: { threshold: [] }\nvariants:\n  - { sampler: jitter }\n' >"$T/emptysweep.yaml"
bad emptysweep '2:21: threshold: the sweep needs a non-empty list'
printf 'scenes: [checker]\nsweep: {}\nvariants:\n  - { sampler: jitter }\n' >"$T/nosweep.yaml"
bad nosweep '2:8: sweep: must map a job key to a list of values'
printf 'scenes: [checker, nowhere]\nvariants:\n  - { sampler: jitter }\n' >"$T/noscene.yaml"
bad noscene '1:19: scene: no scene file at .*scenes/nowhere.yaml'
printf 'scenes: [checker]\nvariants: []\n' >"$T/novariants.yaml"
bad novariants '2:11: variants: must be a non-empty list'
printf 'scenes: [checker]\nvariants:\n  - { sampler: jitter, width: 10 }\n' >"$T/varwidth.yaml"
bad varwidth '3:24: width: not allowed in a variant'
printf 'scenes: [checker]\nsweep: { threshold: [5, 2] }\nvariants:\n  - { sampler: jitter, threshold: 3 }\n' >"$T/swept.yaml"
bad swept '4:24: threshold: swept'
printf 'name: x\nscene: checker\nwidth: 17\nreference: given.png\nvariants:\n  - { sampler: jitter }\n' >"$T/refsize.yaml"
bad refsize '4:12: reference: image is 16x16 but the job renders 17x17'
printf 'scenes: [checker]\nseeds: [1, 2, 1]\nvariants:\n  - { sampler: jitter }\n' >"$T/seeds.yaml"
bad seeds '2:15: seeds: 1 is listed twice'
# two scene files sharing a stem: named, not "listed twice" (issue 27)
mkdir -p "$T/sa" "$T/sb"; cp scenes/checker.yaml "$T/sa/"; cp scenes/checker.yaml "$T/sb/"
printf 'scenes: [sa/checker.yaml, sb/checker.yaml]\nvariants:\n  - { sampler: jitter }\n' >"$T/stems.yaml"
bad stems "1:27: scenes: $T/sa/checker.yaml and $T/sb/checker.yaml are both named \"checker\" .*rename one of the files"
printf 'scenes: [checker]\nsweep: { threshold: [5, 0] }\nvariants:\n  - { sampler: jitter }\n' >"$T/zero.yaml"
bad zero '2:25: threshold: must be a number in \(0, 100\]'
# A compare job stopped by Ctrl-C while its reference renders (nothing written yet) leaves no empty
# OUT/<name>/ behind (it used to make the folder before rendering anything).
cat >"$T/cut.yaml" <<EOF
name: cut
scenes: [$root/scenes/checker.yaml]
width: 200
reference: { sampler: jitter, threshold: 0.5 }
variants:
  - { sampler: jitter }
EOF
# (--preserve-status: timeout's own 124 says only that the second passed, not how the worker ended)
timeout --preserve-status -s INT 1 "$WORKER" --quiet --out "$T/cutout" "$T/cut.yaml" 2>/dev/null; rc=$?
check "a compare job cut short by SIGINT dies by it (got $rc)" [ "$rc" -eq 130 ]
check "a compare job cut short leaves no empty folder" [ ! -e "$T/cutout/cut" ]

# one of each: the summary line says "1 scene", not "1 scenes"
cat >"$T/one.yaml" <<EOF
name: one
scenes: [$root/scenes/checker.yaml]
width: 8
height: 6
reference: { sampler: jitter, threshold: 50 }
variants:
  - { sampler: jitter, threshold: 50 }
EOF
"$WORKER" --out "$T/oneout" "$T/one.yaml" 2>"$T/one.err"; rc=$?
check "a one-image compare job exits 0 (got $rc)" [ "$rc" -eq 0 ]
check "and its summary line is in the singular" grep -q "one: 1 image (1 scene x 1 variant x 1 sweep point x 1 seed)" "$T/one.err"
finish
