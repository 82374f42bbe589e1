#!/bin/sh
# `worker verdict` on forged summary.csv files (issue 36): combinations whose product overflows an
# int are refused in one line (exit 2), not a crash; figures that are not figures (inf, negative,
# huge or text spp and seconds) are left out and said; names that share their first 63 bytes are
# never merged (a name over a compare job's 63 bytes is refused); a large suite is read in time
# linear in its rows.
. tests/lib.sh
root=$(pwd)
ln -s "$root/scenes" "$T/scenes"
cat >"$T/tiny.yaml" <<'YAML'
name: tiny
scenes: [checker]
width: 4
reference: { sampler: jitter, threshold: 10 }
seeds: [1, 2, 3]
sweep: { threshold: [25, 20] }
variants:
  - { label: jit, sampler: jitter }
  - { label: rnd, sampler: random }
YAML
"$WORKER" --quiet --out "$T/out" "$T/tiny.yaml" 2>"$T/tiny.err"; rc=$?
check "tiny study: exit 0 (got $rc: $(tail -n 1 "$T/tiny.err"))" [ "$rc" -eq 0 ]
header=$(head -n 1 "$T/out/tiny/summary.csv")

# 1. 2048 rows, each scene, variant and seed its own: 2048^3 x 1 combinations (an int overflows)
mkdir -p "$T/big"
{
    echo "$header"
    i=0
    while [ $i -lt 2048 ]; do
        echo "s$i,v$i,25,5,$i,16.00,0.01,0.01,0.05,0.01,0.1,0.05,0.05,20,linear,0.08,0.02,,s$i-v$i-t25-s$i.png"
        i=$((i + 1))
    done
} >"$T/big/summary.csv"
"$WORKER" verdict "$T/big" >"$T/big.out" 2>"$T/big.err"; rc=$?
check "2048 distinct scenes, variants, seeds: exit 2 (got $rc), not a crash" [ "$rc" -eq 2 ]
check "... one line saying too many combinations: $(head -c 300 "$T/big.err")" eval \
    '[ "$(wc -l <"$T/big.err")" -eq 1 ] && grep -q "too many combinations" "$T/big.err" && [ ! -s "$T/big.out" ]'

# 7. a field of one row replaced: the image left out and said, never used
forge() { # forge NAME COLUMN VALUE: a copy of the study whose first row's COLUMN is VALUE
    cp -r "$T/out/tiny" "$T/$1"
    python3 - "$T/$1/summary.csv" "$2" "$3" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1], newline='')))
rows[1][rows[0].index(sys.argv[2])] = sys.argv[3]
csv.writer(open(sys.argv[1], 'w', newline=''), lineterminator='\n').writerows(rows)
PY
}
for case in "cpuinf cpu_s inf" "cpuneg cpu_s -3" "cpuhuge cpu_s 1e300" "cputext cpu_s fast" \
    "sppneg samples_per_pixel_mean -16" "spphuge samples_per_pixel_mean 1e300" \
    "spptext samples_per_pixel_mean sixteen" "wallnan wall_s nan" "share sampler_share 7"; do
    set -- $case
    f=$1 key=$2 value=$3
    forge "$f" "$key" "$value"
    "$WORKER" verdict "$T/$f" >"$T/$f.txt" 2>&1; rc=$?
    "$WORKER" verdict "$T/$f" --json >"$T/$f.json" 2>/dev/null
    check "$key=$value: exit 0 (got $rc)" [ "$rc" -eq 0 ]
    check "$key=$value: the figure is not used: $(grep -i "inf s\|e+300\|-3 s" "$T/$f.txt" | head -n 1)" eval \
        '! grep -qi "inf s\|e+300\|nan s\|-3 s\|-16 per" "$T/$f.txt"'
    check "$key=$value: one image left out, said in a warning" python3 - "$T/$f.json" <<'PY'
import json, sys
x = json.load(open(sys.argv[1]))['studies'][0]['scenes'][0]
assert any(w.startswith('left out: 1 image whose samples_per_pixel_mean, wall_s, cpu_s or sampler_share')
           for w in x['warnings']), x['warnings']
PY
done

# 7. two variants whose names share their first 63 bytes stay two, or are refused: never one
long=$(printf 'v%.0s' $(seq 1 63))
mkdir -p "$T/long"
{
    echo "$header"
    for v in a b; do
        for k in 1 2 3; do
            echo "checker,$long$v,25,5,$k,16.00,0.01,0.01,0.05,0.01,0.1,0.05,0.05,20,linear,0.08,0.02,,checker-$long$v-t25-s$k.png"
        done
    done
} >"$T/long/summary.csv"
"$WORKER" verdict "$T/long" --json >"$T/long.json" 2>"$T/long.err"; rc=$?
check "variant names sharing 63 bytes: never merged into one (exit $rc: $(cat "$T/long.err"))" python3 - "$T/long.json" "$rc" "$T/long.err" <<'PY'
import json, sys
if sys.argv[2] == '2':
    err = open(sys.argv[3]).read()
    assert err.count('\n') == 1 and 'summary.csv:2:' in err and 'variant: 64 bytes' in err, err
else:
    x = json.load(open(sys.argv[1]))['studies'][0]['scenes'][0]
    assert len(x['equal_samples']['ranking']) == 2, x['equal_samples']
PY

# a seed that is no whole number, a threshold that is no number: one line, exit 2
for case in "seed x1" "threshold abc"; do
    set -- $case
    key=$1 value=$2
    forge "bad$key" "$key" "$value"
    "$WORKER" verdict "$T/bad$key" >/dev/null 2>"$T/bad$key.err"; rc=$?
    check "$key=$value: exit 2 (got $rc), one line naming summary.csv:2: $(cat "$T/bad$key.err")" eval \
        '[ "$rc" -eq 2 ] && [ "$(wc -l <"$T/bad$key.err")" -eq 1 ] && grep -q "summary.csv:2:" "$T/bad$key.err"'
done
finish
