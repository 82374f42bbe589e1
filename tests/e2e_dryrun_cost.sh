#!/bin/sh
# End to end (issues 35, 36): --dry-run's CPU estimate, by the cost model, is within 2x of the
# render's own CPU seconds (its sidecar's cpu_s) for sets too large to draw per sample (2x2
# images, poisson t=0.25 and pmj02bn t=0.5: the pilot charged a whole set to one path, 4488 s
# and 5.9 h estimated for renders of a second) and for small shrunk copies of the shipped
# studies; and the dry run of a compare job of 4096 combinations (the most one may have) takes
# under 10 s of CPU by its own account.
. tests/lib.sh
root=$(pwd)

est_cpu() { # est_cpu FILE: the estimate's CPU seconds from a plain job's dry-run output
    python3 - "$1" <<'PY'
import re, sys
m = re.search(r'^  CPU time  about ([0-9.e+]+) (ms|s|min|h)\b', open(sys.argv[1]).read(), re.M)
print(float(m.group(1)) * {'ms': 1e-3, 's': 1, 'min': 60, 'h': 3600}[m.group(2)])
PY
}
took() { # took FILE: the CPU seconds the dry run says it took
    sed -n 's/^  dry run   took \([0-9.e+-]*\) s of CPU$/\1/p' "$1"
}
within2() { # within2 A B: A / B in [1/2, 2]
    python3 -c 'import sys; r = float(sys.argv[1]) / float(sys.argv[2]); sys.exit(0 if 0.5 <= r <= 2 else 1)' "$1" "$2"
}

for s in "poisson 0.25" "pmj02bn 0.5"; do
    set -- $s
    printf 'name: %s\nscene: %s/scenes/checker.yaml\nwidth: 2\nheight: 2\nsampler: %s\nthreshold: %s\nprocesses: 1\n' \
        "$1" "$root" "$1" "$2" >"$T/$1.yaml"
    "$WORKER" "$T/$1.yaml" --dry-run >"$T/$1.dry" 2>&1
    "$WORKER" --quiet --out "$T/out" "$T/$1.yaml" 2>/dev/null
    est=$(est_cpu "$T/$1.dry")
    real=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["time"]["cpu_s"])' "$T/out/$1/$1.json")
    check "$1 t=$2, 2x2: estimate $est s within 2x of the render's $real s ($(cat "$T/$1.dry"))" within2 "$est" "$real"
    check "$1 t=$2: the dry run says what it took ($(took "$T/$1.dry") s)" python3 -c 'import sys; assert float(sys.argv[1]) < 10' "$(took "$T/$1.dry")"
done

# the shipped studies, shrunk (24 pixels wide, 2 seeds, a cheap reference; error-look, whose images
# take 1 to 4 samples a pixel, 64 wide: at 24 its 12 images took 7 ms in all, where a millisecond of
# load moved the ratio past 2x): each study's images' estimate against the sum of their sidecars'
# cpu_s (not under ASan: its costs are not a release build's, and the renders take minutes there)
mkdir -p "$T/jobs/studies"
ln -s "$root/scenes" "$T/scenes"
studies="$root/jobs/studies/*.yaml"
[ "${ASAN_FAST:-0}" = 1 ] && studies=""
for f in $studies; do
    study=$(basename "$f" .yaml)
    width=24
    [ "$study" = error-look ] && width=64
    python3 - "$f" "$T/jobs/studies/$study.yaml" "$width" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
text = re.sub(r'(?m)^width: *\d+', 'width: ' + sys.argv[3], text)
text = re.sub(r'(?m)^seeds: *\[.*\]', 'seeds: [1, 2]', text)
text = re.sub(r'(?m)^reference: *\{[^}]*\}', 'reference: { sampler: jitter, threshold: 20 }', text)
assert 'width: ' + sys.argv[3] in text and 'seeds: [1, 2]' in text, 'study file shape changed: ' + sys.argv[1]
open(sys.argv[2], 'w').write(text)
PY
    "$WORKER" "$T/jobs/studies/$study.yaml" --dry-run >"$T/$study.dry" 2>&1
    "$WORKER" --quiet --out "$T/out" "$T/jobs/studies/$study.yaml" >/dev/null 2>&1
    est=$(python3 - "$T/$study.dry" <<'PY'
import re, sys
m = re.search(r'^  images .* CPU about ([0-9.e+]+) (ms|s|min|h)$', open(sys.argv[1]).read(), re.M)
print(float(m.group(1)) * {'ms': 1e-3, 's': 1, 'min': 60, 'h': 3600}[m.group(2)])
PY
)
    real=$(python3 -c 'import csv, sys; print(sum(float(r["cpu_s"]) for r in csv.DictReader(open(sys.argv[1]))))' "$T/out/$study/summary.csv")
    check "$study (shrunk): estimate $est s within 2x of its images' $real s ($(cat "$T/$study.dry"))" within2 "$est" "$real"
done

# 4096 combinations: 16 variants (every sampler, pools, both domains, sampler_dims: all) x 256
# sweep points from t=100 down to t=0.98 (sets of 10^4 points); the old dry run drew a whole set
# in each of 4096 pilots
{
    printf 'name: big\nscenes: [%s/scenes/checker.yaml]\nwidth: 16\nheight: 16\nseeds: [1]\n' "$root"
    python3 -c 'print("sweep: { threshold: [%s] }" % ", ".join("%.4g" % (100 * 0.982 ** i) for i in range(256)))'
    printf 'variants:\n'
    for v in uniform jitter random poisson sobol halton pmj02bn zsobol; do
        printf '  - { sampler: %s, light_sampler: %s }\n' $v $v
    done
    printf '  - { label: pool, sampler: poisson, light_sampler: poisson, poisson_pool: 64 }\n'
    printf '  - { label: square, sampler: poisson, light_sampler: poisson, poisson_domain: square }\n'
    for v in jitter sobol pmj02bn zsobol poisson halton; do
        printf '  - { label: %s-dims, sampler: %s, sampler_dims: all, integrator: nee }\n' $v $v
    done
} >"$T/big.yaml"
"$WORKER" "$T/big.yaml" --dry-run >"$T/big.dry" 2>&1; rc=$?
check "4096 combinations: exit 0 (got $rc: $(tail -n 3 "$T/big.dry"))" [ "$rc" -eq 0 ]
check "4096 combinations: all counted" grep -q "^  images    4096 (1 scene x 16 variants x 256 points x 1 seed)" "$T/big.dry"
if [ "${ASAN_FAST:-0}" = 1 ]; then # the bound is the release build's; ASan's is several times slower
    skip "4096 combinations: under 10 s of CPU (ASan build: took $(took "$T/big.dry") s)"
else
    check "4096 combinations: the dry run took under 10 s of CPU ($(took "$T/big.dry") s)" \
        python3 -c 'import sys; assert 0 < float(sys.argv[1]) < 10' "$(took "$T/big.dry")"
fi
check "4096 combinations: one seed warned about" grep -q "^  warning: one seed: no spread across seeds" "$T/big.dry"
finish
