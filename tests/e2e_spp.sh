#!/bin/sh
# A compare job's sweep in samples per pixel (issue 36): `sweep: { spp: [1, 4, 16] }` gives each
# variant the threshold at which its sampler draws that many camera samples (jitter and pmj02bn
# exactly, poisson about), said in the report; an spp a sampler cannot give exactly, spp beside
# threshold, and a variant's own threshold are errors at line:col.
. tests/lib.sh
root=$(pwd)
ln -s "$root/scenes" "$T/scenes"
cat >"$T/spp.yaml" <<'YAML'
name: sppsweep
scenes: [checker]
width: 4
reference: { sampler: jitter, threshold: 10 }
seeds: [1, 2]
sweep: { spp: [1, 4, 16] }
variants:
  - { label: jit, sampler: jitter }
  - { label: pmj, sampler: pmj02bn }
  - { label: poi, sampler: poisson }
YAML
"$WORKER" --quiet --out "$T/out" "$T/spp.yaml" 2>"$T/spp.err"; rc=$?
check "spp sweep: exit 0 (got $rc: $(tail -n 1 "$T/spp.err"))" [ "$rc" -eq 0 ]
check "spp sweep: each variant's threshold gives it the spp (poisson about)" python3 - "$T/out/sppsweep/summary.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1], newline='')))
assert len(rows) == 18, len(rows)
want = {'1': 100, '4': 50, '16': 25}
for r in rows:
    spp = r['image'].split('-spp')[1].split('-')[0]
    got = float(r['samples_per_pixel_mean'])
    if r['variant'] == 'poi':
        assert abs(float(r['threshold']) - (6150 / int(spp)) ** 0.5) < 0.01, r
        assert 0.7 * int(spp) <= got <= 1.3 * int(spp), r
    else:
        assert float(r['threshold']) == want[spp] and got == int(spp), r
PY
check "spp sweep: the report says how the sweep was given" \
    grep -q "sweep: spp (each variant&#39;s threshold set so its sampler draws that many camera samples" \
    "$T/out/sppsweep/report.html"
check "spp sweep: the points are labelled by spp" grep -q 'spp 16: pixels' "$T/out/sppsweep/report.html"
"$WORKER" verdict "$T/out/sppsweep" --json >"$T/again.json" 2>"$T/again.err"; rc=$?
check "worker verdict on it: exit 0 (got $rc), its points named by spp as the run named them" python3 - \
    "$T/out/sppsweep/verdict.json" "$T/again.json" <<'PY'
import json, sys
a, b = (json.load(open(p))['studies'][0]['scenes'][0] for p in sys.argv[1:3])
ta, tb = sorted(f['text'] for f in a['failures']), sorted(f['text'] for f in b['failures'])
assert ta == tb, (ta, tb)
assert not any('threshold' in t for t in tb), tb
PY
bad() { # bad NAME SED-EXPRESSION WANT: the job edited by SED-EXPRESSION fails with WANT, exit 2
    name=$1 want=$3
    sed "$2" "$T/spp.yaml" >"$T/$name.yaml"
    "$WORKER" --quiet --out "$T/out" "$T/$name.yaml" 2>"$T/$name.err"; rc=$?
    check "$name: exit 2 (got $rc), one line: $(cat "$T/$name.err")" eval \
        '[ "$rc" -eq 2 ] && [ "$(wc -l <"$T/$name.err")" -eq 1 ] && grep -q "$want" "$T/$name.err"'
}
bad notsquare 's/spp: \[1, 4, 16\]/spp: [1, 8]/' \
    "$T/notsquare.yaml:6:19: spp: 8: jitter sets hold n x n points (n = floor(100 / threshold)): 4 or 9, not 8"
bad notpow2 's/spp: \[1, 4, 16\]/spp: [1, 9, 16]/' "notpow2.yaml:6:19: spp: 9: pmj02bn sets hold n x n points rounded up to a power of two (n = floor(100 / threshold)): 4 or 16, not 9"
bad both 's/spp: \[1, 4, 16\]/spp: [1, 4], threshold: [5, 6]/' \
    "both.yaml:6:10: spp: and threshold: both set the camera sampler's threshold"
bad variant 's/label: jit, sampler: jitter/label: jit, sampler: jitter, threshold: 5/' \
    "variant.yaml:8:36: threshold: swept (sweep: spp), so a variant cannot set it"
bad zero 's/spp: \[1, 4, 16\]/spp: [0, 4]/' 'zero.yaml:6:16: spp: must be in \[1, 4000000\]'
finish
