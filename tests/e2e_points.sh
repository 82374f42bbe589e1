#!/bin/sh
# `worker points`: CSV sets of the right size inside [0,1), an SVG drawing, clear errors.
. tests/lib.sh
count() { "$WORKER" points "$@" | wc -l; }
check "uniform t=5 prints 400 points" [ "$(count uniform 5)" -eq 400 ]
check "jitter t=3 prints 1089 points" [ "$(count jitter 3)" -eq 1089 ]
check "random t=1 prints 10000 points" [ "$(count random 1)" -eq 10000 ]
n=$(count poisson 1 --seed 4)
check "poisson t=1 prints 6000..6700 points (got $n)" [ "$n" -ge 6000 ] && [ "$n" -le 6700 ]
check "every line is x,y with two numbers" sh -c "'$WORKER' points poisson 10 | awk -F, 'NF != 2 || \$1 !~ /^0\\.[0-9]+$/ || \$2 !~ /^0\\.[0-9]+$/ {bad = 1} END {exit bad}'"
"$WORKER" points poisson 5 --seed 2 >"$T/a.csv"
"$WORKER" points poisson 5 --seed 2 >"$T/b.csv"
"$WORKER" points poisson 5 --seed 3 >"$T/c.csv"
check "same seed, same set" cmp -s "$T/a.csv" "$T/b.csv"
check "other seed, other set" sh -c "! cmp -s '$T/a.csv' '$T/c.csv'"
check "all points in [0,1)" awk -F, '($1 < 0 || $1 >= 1 || $2 < 0 || $2 >= 1) {bad = 1} END {exit bad}' "$T/a.csv"
"$WORKER" points jitter 20 --svg "$T/p.svg" >/dev/null
check "svg written" grep -q '<svg' "$T/p.svg"
check "svg draws 25 points" [ "$(grep -o '<circle' "$T/p.svg" | wc -l)" -eq 25 ]
"$WORKER" points halton 5 >/dev/null 2>"$T/e1"; rc=$?
check "unknown sampler exits 2" [ "$rc" -eq 2 ]
check "unknown sampler message" grep -q 'unknown sampler "halton"' "$T/e1"
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
finish
