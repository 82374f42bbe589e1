#!/bin/sh
# `worker points` for halton, pmj02bn and zsobol: sizes (powers of two where stated), pmj02bn's
# 256 points a (0,8,2)-net for several seeds, and the analyses (--stats, --spectrum, --radial).
. tests/lib.sh
# 1 when the 2^m points of CSV file $1 form a (0,m,2)-net: each elementary interval of area 2^-m
# holds one point (the printed six decimals are exact enough for the seeds below)
is_net() {
    awk -F, -v m="$2" '{ x[NR] = $1; y[NR] = $2 }
        END { if (NR != 2 ^ m) exit 1
              for (a = 0; a <= m; a++) { delete c
                  for (i = 1; i <= NR; i++) { k = int(x[i] * 2 ^ a) "," int(y[i] * 2 ^ (m - a)); if (c[k]++) exit 1 } }
              exit 0 }' "$1"
}
for s in 1 2 3 4; do
    "$WORKER" points pmj02bn 6.25 --seed $s >"$T/p$s.csv"
    check "pmj02bn 6.25 seed $s: 256 points" [ "$(wc -l <"$T/p$s.csv")" -eq 256 ]
    check "pmj02bn 6.25 seed $s: a (0,8,2)-net" is_net "$T/p$s.csv" 8
    head -64 "$T/p$s.csv" >"$T/h$s.csv"
    check "pmj02bn seed $s: its first 64 points a (0,6,2)-net" is_net "$T/h$s.csv" 6
done
check "pmj02bn: other seed, other set" sh -c "! cmp -s '$T/p1.csv' '$T/p2.csv'"
# the check can fail: a halton set (not a base-2 net)
"$WORKER" points halton 6.25 >"$T/h.csv"
check "halton 6.25: 256 points" [ "$(wc -l <"$T/h.csv")" -eq 256 ]
if is_net "$T/h.csv" 8; then net=1; else net=0; fi
check "halton is no (0,8,2)-net (the check can fail)" [ "$net" -eq 0 ]
"$WORKER" points zsobol 6.25 --seed 5 >"$T/z.csv"
check "zsobol 6.25: a (0,8,2)-net" is_net "$T/z.csv" 8
check "halton 10: n*n = 100 points" [ "$("$WORKER" points halton 10 | wc -l)" -eq 100 ]
check "pmj02bn 10: 100 rounded up to 128 points" [ "$("$WORKER" points pmj02bn 10 | wc -l)" -eq 128 ]
check "zsobol 10: 128 points" [ "$("$WORKER" points zsobol 10 | wc -l)" -eq 128 ]
for k in halton pmj02bn zsobol; do
    "$WORKER" points $k 12.5 --sets 4 --stats --spectrum "$T/$k.png" --radial "$T/$k.svg" --svg "$T/${k}p.svg" \
        >"$T/$k.stats"; rc=$?
    check "$k: --stats --spectrum --radial --svg exit 0 (got $rc)" [ "$rc" -eq 0 ]
    check "$k: stats name the sampler and count 64" sh -c "grep -q '^sampler $k' '$T/$k.stats' && grep -q '^count 64' '$T/$k.stats'"
    check "$k: spectrum PNG and radial SVG written" sh -c "[ -s '$T/$k.png' ] && grep -q '<svg' '$T/$k.svg'"
done
"$WORKER" points zsobol 0.05 >/dev/null 2>"$T/e"; rc=$?
check "zsobol 0.05 (2000^2 rounds up past the limit): exit 2 naming 4194304" sh -c "[ $rc -eq 2 ] && grep -q 4194304 '$T/e'"
finish
