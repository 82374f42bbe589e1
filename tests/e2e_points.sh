#!/bin/sh
# `worker points`: CSV sets of the right size inside [0,1), an SVG drawing, clear errors.
. tests/lib.sh
count() { "$WORKER" points "$@" | wc -l; }
check "uniform t=5 prints 400 points" [ "$(count uniform 5)" -eq 400 ]
check "jitter t=3 prints 1089 points" [ "$(count jitter 3)" -eq 1089 ]
check "random t=1 prints 10000 points" [ "$(count random 1)" -eq 10000 ]
n=$(count poisson 1 --seed 4)
check "poisson t=1 prints 6000..6700 points (got $n)" eval '[ "$n" -ge 6000 ] && [ "$n" -le 6700 ]'
num='/^(0|0\.[0-9]+|[1-9](\.[0-9]+)?e-[0-9]+)$/'
check "every line is x,y with two numbers" sh -c "'$WORKER' points poisson 10 | awk -F, 'NF != 2 || \$1 !~ $num || \$2 !~ $num {bad = 1} END {exit bad}'"
# 17 significant digits: every point of a 200 x 200 jitter set reads back in its own cell (with 6
# decimals about 8 points within 5e-7 below a boundary were printed in the next cell)
check "jitter t=0.5: every point read back lands in its own cell, one per cell" sh -c "'$WORKER' points jitter 0.5 --seed 5 | awk -F, '{c[int(\$1 * 200) * 200 + int(\$2 * 200)]++} END {for (i = 0; i < 40000; i++) if (c[i] != 1) exit 1}'"
"$WORKER" points poisson 5 --seed 2 >"$T/a.csv"
"$WORKER" points poisson 5 --seed 2 >"$T/b.csv"
"$WORKER" points poisson 5 --seed 3 >"$T/c.csv"
check "same seed, same set" cmp -s "$T/a.csv" "$T/b.csv"
check "other seed, other set" sh -c "! cmp -s '$T/a.csv' '$T/c.csv'"
check "all points in [0,1)" awk -F, '($1 < 0 || $1 >= 1 || $2 < 0 || $2 >= 1) {bad = 1} END {exit bad}' "$T/a.csv"
"$WORKER" points jitter 20 --svg "$T/p.svg" >/dev/null
check "svg written" grep -q '<svg' "$T/p.svg"
check "svg draws 25 points" [ "$(grep -o '<circle' "$T/p.svg" | wc -l)" -eq 25 ]
"$WORKER" points stratified 5 >/dev/null 2>"$T/e1"; rc=$?
check "unknown sampler exits 2" [ "$rc" -eq 2 ]
check "unknown sampler message" grep -q 'unknown sampler "stratified"' "$T/e1"
"$WORKER" points Uniform 5 >/dev/null 2>"$T/e6"; rc=$?
check "a near miss gets a did you mean (exit $rc)" sh -c "[ $rc -eq 2 ] && grep -q 'did you mean \"uniform\"' '$T/e6'"
"$WORKER" points uniform abc >/dev/null 2>"$T/e2"; rc=$?
check "bad threshold exits 2" [ "$rc" -eq 2 ]
for t in 0x10 " 5" 1e1x; do
    "$WORKER" points uniform "$t" >/dev/null 2>"$T/e5"; rc=$?
    check "threshold \"$t\" is refused as in a job file (exit 2, got $rc)" sh -c "[ $rc -eq 2 ] && grep -q 'threshold: must be a number' '$T/e5'"
done
"$WORKER" points uniform 0.01 >/dev/null 2>"$T/e3"; rc=$?
check "oversized set exits 2 naming the count" sh -c "[ $rc -eq 2 ] && grep -q 100000000 '$T/e3'"
# --quiet is a common option: accepted by points and diff, before the subcommand too
"$WORKER" points uniform 20 --quiet >"$T/q1.csv" 2>"$T/q1.err"; rc=$?
check "points ... --quiet: exit 0 and 25 points (got $rc)" sh -c "[ $rc -eq 0 ] && [ \$(wc -l <'$T/q1.csv') -eq 25 ]"
"$WORKER" --quiet points uniform 20 >"$T/q2.csv" 2>"$T/q2.err"; rc=$?
check "--quiet points ...: exit 0 and the same points (got $rc)" sh -c "[ $rc -eq 0 ] && cmp -s '$T/q1.csv' '$T/q2.csv'"
printf 'P3\n1 1\n255\n1 2 3\n' >"$T/one.ppm"
"$WORKER" diff "$T/one.ppm" "$T/one.ppm" --max-rmse 0 --quiet >"$T/d1.out" 2>"$T/d1.err"; rc=$?
check "diff ... --quiet: exit 0 with the metrics (got $rc)" sh -c "[ $rc -eq 0 ] && grep -q '^rmse 0' '$T/d1.out'"
"$WORKER" --quiet diff "$T/one.ppm" "$T/one.ppm" >"$T/d2.out" 2>"$T/d2.err"; rc=$?
check "--quiet diff ...: exit 0 with the metrics (got $rc)" sh -c "[ $rc -eq 0 ] && grep -q '^rmse 0' '$T/d2.out'"
"$WORKER" points uniform >/dev/null 2>"$T/e4"; rc=$?
check "points without a threshold: exit 2, one line saying what is missing" sh -c "[ $rc -eq 2 ] && [ \$(wc -l <'$T/e4') -eq 1 ] && grep -q '^worker points: ' '$T/e4'"
# diff's numbers are finite decimals: --max-rmse nan compared false with every rmse (exit 0)
for v in nan inf 0x0; do
    "$WORKER" diff "$T/one.ppm" "$T/one.ppm" --max-rmse "$v" >/dev/null 2>"$T/d3.err"; rc=$?
    check "diff --max-rmse $v is a usage error (exit 2, got $rc)" [ "$rc" -eq 2 ]
done
# --help and --version before a subcommand still answer (exit 0), as they did before it was hoisted
"$WORKER" --help diff >"$T/h1.out" 2>"$T/h1.err"; rc=$?
check "--help diff: exit 0 with the usage (got $rc)" sh -c "[ $rc -eq 0 ] && grep -q 'usage: worker' '$T/h1.out'"
"$WORKER" --version points >"$T/v1.out" 2>"$T/v1.err"; rc=$?
check "--version points: exit 0 with the version (got $rc)" sh -c "[ $rc -eq 0 ] && grep -Eq '^worker [0-9]' '$T/v1.out'"
# --help after a subcommand answers with that subcommand's usage, exit 0
"$WORKER" diff --help >"$T/dh.out" 2>"$T/dh.err"; rc=$?
check "diff --help: exit 0 and its usage on stdout (got $rc)" sh -c "[ $rc -eq 0 ] && grep -q '^usage: worker diff' '$T/dh.out' && [ ! -s '$T/dh.err' ]"
"$WORKER" points --help >"$T/ph.out" 2>"$T/ph.err"; rc=$?
check "points --help: exit 0 and its usage on stdout (got $rc)" sh -c "[ $rc -eq 0 ] && grep -q '^usage: worker points' '$T/ph.out'"
# sobol: 256 points at t=6.25 forming a (0,8,2)-net: every elementary interval of area 1/256
# (2^a x 2^b boxes, a + b = 8) holds exactly one point, for several seeds
net() { # net FILE M: FILE's points are 2^M and every 2^a x 2^b box (a + b = M) holds one
    awk -F, -v m="$2" '{x[NR] = $1; y[NR] = $2} END {
        bad = NR != 2 ^ m
        for (a = 0; a <= m; a++) { b = m - a; delete c
            for (i = 1; i <= NR; i++) if (c[int(x[i] * 2 ^ a) * 65536 + int(y[i] * 2 ^ b)]++) bad = 1 }
        exit bad }' "$1"
}
check "sobol t=6.25 prints 256 points" [ "$(count sobol 6.25)" -eq 256 ]
# a threshold within a relative 1e-9 of 100 / n gives n, as a person reads it
check "jitter t=6.250000001 prints 256 points" [ "$(count jitter 6.250000001)" -eq 256 ]
check "jitter t=9.0909090919 prints 121 points" [ "$(count jitter 9.0909090919)" -eq 121 ]
for s in 1 2 7; do
    "$WORKER" points sobol 6.25 --seed $s >"$T/net$s.csv"
    check "sobol t=6.25 seed $s: 256 points forming a (0,8,2)-net" net "$T/net$s.csv" 8
done
"$WORKER" points sobol 25 --seed 3 >"$T/s16.csv"
check "sobol t=25: 16 points forming a (0,4,2)-net" net "$T/s16.csv" 4
"$WORKER" points jitter 6.25 >"$T/j256.csv"
fails() { ! "$@"; }
check "a jittered set of 256 is no (0,8,2)-net (the check can fail)" fails net "$T/j256.csv" 8
"$WORKER" points sobol 3 --seed 5 >"$T/s1.csv"
"$WORKER" points sobol 3 --seed 5 >"$T/s2.csv"
"$WORKER" points sobol 3 --seed 6 >"$T/s3.csv"
check "sobol: same seed, same set; 1089 points" sh -c "cmp -s '$T/s1.csv' '$T/s2.csv' && [ \$(wc -l <'$T/s1.csv') -eq 1089 ]"
check "sobol: other seed, other set" sh -c "! cmp -s '$T/s1.csv' '$T/s3.csv'"

# --spectrum, --radial and --stats work for every sampler
stat() { awk -v k="$1" '$1 == k {print $2}' "$2"; }
for s in uniform jitter random poisson sobol; do
    "$WORKER" points $s 6.25 --sets 4 --stats --spectrum "$T/$s.png" --radial "$T/$s.svg" >"$T/$s.stats" 2>"$T/$s.err"; rc=$?
    check "$s: --spectrum --radial --stats exit 0 (got $rc: $(head -c 200 "$T/$s.err"))" [ "$rc" -eq 0 ]
    check "$s: the spectrum is a PNG" sh -c "head -c 8 '$T/$s.png' | od -An -c | grep -q 'P   N   G'"
    check "$s: the radial chart is an SVG with two panels" sh -c "grep -q '<svg' '$T/$s.svg' && grep -q 'radial mean power' '$T/$s.svg' && grep -q 'anisotropy' '$T/$s.svg'"
    check "$s: the radial chart's title names the seeds' whole range (it was cut: \"seeds 1..\")" \
        grep -q "radial spectrum over 4 sets, seeds 1\.\.4</text>" "$T/$s.svg"
    for k in count min_distance min_distance_toroidal star_discrepancy_l2 low_frequency_power; do
        check "$s: --stats prints $k" sh -c "[ -n \"\$(awk '\$1 == \"$k\" {print \$2}' '$T/$s.stats')\" ]"
    done
    check "$s: --stats prints no points" sh -c "! grep -q '^0\\.[0-9]*,' '$T/$s.stats'"
done
check "sobol --stats: count 256" [ "$(stat count "$T/sobol.stats")" = 256 ]
check "uniform --stats: min distance 1/16 plain and toroidal" sh -c "[ '$(stat min_distance "$T/uniform.stats")' = 0.0625 ] && [ '$(stat min_distance_toroidal "$T/uniform.stats")' = 0.0625 ]"
check "--stats names the sets' seeds" grep -q '^sets 4 (seeds 1\.\.4)$' "$T/sobol.stats"
check "--stats says which minimum distance is which" sh -c "grep -q '^min_distance .*not toroidal' '$T/sobol.stats' && grep -q '^min_distance_toroidal .*modulo 1' '$T/sobol.stats'"
# random's low frequencies at ~1 (16 sets of 256: 196 frequencies each, standard error ~0.03),
# jitter's, poisson's and sobol's well below
"$WORKER" points random 6.25 --sets 16 --stats >"$T/r16.stats"
lf=$(stat low_frequency_power "$T/r16.stats")
check "random: low-frequency power 1 within 0.15 (got $lf)" awk -v v="$lf" 'BEGIN {exit !(v > 0.85 && v < 1.15)}'
for s in jitter poisson sobol; do
    lf=$(stat low_frequency_power "$T/$s.stats")
    check "$s: low-frequency power below 0.5 (got $lf)" awk -v v="$lf" 'BEGIN {exit !(v < 0.5)}'
done
d_r=$(stat star_discrepancy_l2 "$T/random.stats"); d_s=$(stat star_discrepancy_l2 "$T/sobol.stats")
check "sobol's discrepancy below random's ($d_s < $d_r)" awk -v a="$d_s" -v b="$d_r" 'BEGIN {exit !(a < b / 3)}'
"$WORKER" points sobol 6.25 --sets 4 --stats >"$T/again.stats"
check "--stats: the same seeds, the same figures" cmp -s "$T/sobol.stats" "$T/again.stats"
"$WORKER" points sobol 6.25 --spectrum "$T/one.png" >"$T/one.csv"
check "--spectrum alone still prints the set" [ "$(wc -l <"$T/one.csv")" -eq 256 ]
# bounded: too much work is refused before anything is written
"$WORKER" points random 0.5 --spectrum "$T/big.png" >"$T/big.out" 2>"$T/big.err"; rc=$?
check "an oversized spectrum: exit 2, the limit named, no file, no points" sh -c "[ $rc -eq 2 ] && grep -q 'limit' '$T/big.err' && [ ! -e '$T/big.png' ] && [ ! -s '$T/big.out' ]"
"$WORKER" points random 0.3 --stats >/dev/null 2>"$T/big2.err"; rc=$?
check "oversized --stats: exit 2 naming the point pairs" sh -c "[ $rc -eq 2 ] && grep -q 'point pairs' '$T/big2.err'"
for v in 0 -1 x 100001; do
    "$WORKER" points random 5 --sets "$v" --stats >/dev/null 2>"$T/sets.err"; rc=$?
    check "--sets $v: exit 2" sh -c "[ $rc -eq 2 ] && grep -q -- '--sets' '$T/sets.err'"
done
"$WORKER" points random 5 --spectrum "$T/nodir/x.png" >/dev/null 2>"$T/nd.err"; rc=$?
check "--spectrum into a missing folder: exit 2" sh -c "[ $rc -eq 2 ] && grep -q 'no folder' '$T/nd.err'"
# --padded K: K dimensions per sample of pixel (0, 0), the pixel's own set then the padded slots
"$WORKER" points jitter 25 --padded 4 --seed 3 >"$T/pad.csv"; rc=$?
check "--padded 4 exits 0 (got $rc)" [ "$rc" -eq 0 ]
check "--padded 4 on a 4x4 grid: 16 rows of 8 numbers" sh -c "[ \$(wc -l <'$T/pad.csv') -eq 16 ] && awk -F, 'NF != 8 {bad = 1} END {exit bad}' '$T/pad.csv'"
for d in 0 1 2 3; do
    check "--padded: dimension $d puts one sample in each of the 16 cells" sh -c "awk -F, -v d=$d '{c[int(\$(2*d+1)*4) + 4*int(\$(2*d+2)*4)]++} END {for (i = 0; i < 16; i++) if (c[i] != 1) exit 1}' '$T/pad.csv'"
done
check "--padded: the padded dimensions are in other orders than the pixel's" sh -c "awk -F, '{if (int(\$1*4) == int(\$3*4) && int(\$2*4) == int(\$4*4)) same++} END {exit same == 16}' '$T/pad.csv'"
"$WORKER" points jitter 25 --padded 4 --seed 3 >"$T/pad2.csv"
"$WORKER" points jitter 25 --padded 4 --seed 4 >"$T/pad3.csv"
check "--padded: same seed, same rows" cmp -s "$T/pad.csv" "$T/pad2.csv"
check "--padded: other seed, other rows" sh -c "! cmp -s '$T/pad.csv' '$T/pad3.csv'"
n=$("$WORKER" points sobol 10 --padded 2 | wc -l)
check "--padded with sobol t=10: 100 rows (got $n)" [ "$n" -eq 100 ]
"$WORKER" points jitter 25 --padded 0 >/dev/null 2>"$T/pad.err"; rc=$?
check "--padded 0: exit 2" sh -c "[ $rc -eq 2 ] && grep -q -- '--padded: must be a whole number' '$T/pad.err'"
"$WORKER" points jitter 25 --padded 2 --stats >/dev/null 2>"$T/pad.err"; rc=$?
check "--padded with --stats: exit 2" sh -c "[ $rc -eq 2 ] && grep -q -- '--padded prints' '$T/pad.err'"
finish
