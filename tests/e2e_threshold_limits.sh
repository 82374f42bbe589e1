#!/bin/sh
# e2e_threshold_limits: a threshold too small for the per-set limit is refused the same way by all
# four samplers (pixel and light): exit 2, one line at the key's line:col naming the count, the
# limit, why, and the smallest threshold that sampler takes; and that smallest threshold renders.
. "$(dirname "$0")/lib.sh"
S=$(pwd)/scenes/checker.yaml
smallest() { case $1 in poisson) echo 0.0708 ;; *) echo 0.05 ;; esac; }
for s in uniform jitter random poisson; do
    for t in 0.05 0.01 0.001; do
        [ "$s" != poisson ] && [ "$t" = 0.05 ] && continue # within the limit for the grid kinds
        for key in threshold light_threshold; do
            other=threshold; [ "$key" = threshold ] && other=light_threshold
            printf 'scene: %s\nwidth: 1\nsampler: %s\nlight_sampler: %s\n%s: %s\n%s: 50\n' "$S" "$s" "$s" "$key" "$t" \
                "$other" >"$T/j.yaml"
            rm -rf "$T/out"
            "$WORKER" --quiet --out "$T/out" "$T/j.yaml" 2>"$T/err"; rc=$?
            check "$s $key $t: exit 2 (got $rc)" [ "$rc" -eq 2 ]
            check "$s $key $t: says the limit and the smallest threshold: $(cat "$T/err")" \
                grep -q "^$T/j.yaml:5:[0-9]*: $key: $t would need [0-9]* [a-zA-Z ]* per $s set (limit 4000000 per set, each set held whole in memory); the smallest $s $key is $(smallest "$s")\$" "$T/err"
            check "$s $key $t: nothing written" [ ! -e "$T/out" ]
        done
    done
    # the smallest threshold it names is taken (a 1x1 image, one process)
    printf 'scene: %s\nwidth: 1\nheight: 1\nprocesses: 1\nsampler: %s\nthreshold: %s\nlight_threshold: 50\n' "$S" "$s" \
        "$(smallest "$s")" >"$T/j.yaml"
    "$WORKER" --quiet --out "$T/out" "$T/j.yaml" 2>"$T/err"; rc=$?
    check "$s at its smallest threshold $(smallest "$s"): renders (rc $rc: $(cat "$T/err"))" [ "$rc" -eq 0 ]
    "$WORKER" points "$s" 0.001 >/dev/null 2>"$T/err"; rc=$?
    check "points $s 0.001: refused, exit 2 (got $rc)" [ "$rc" -eq 2 ]
done

# Issue 27: a Poisson pool and a fresh Poisson light set per pixel are inside the up-front
# limits too, refused at their key before anything is drawn (they took 25 s and 1.26 GB for a
# 1x1 image, and 66 CPU-hours)
refused() { # refused WHAT FILE REGEX: exit 2, the message at the key's line:col, nothing written
    rm -rf "$T/out"
    "$WORKER" --quiet --out "$T/out" "$2" 2>"$T/err"; rc=$?
    check "$1: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "$1: at the key's line:col: $(cat "$T/err")" grep -q "^$2:$3" "$T/err"
    check "$1: nothing written" [ ! -e "$T/out" ]
}
printf 'scene: %s\nwidth: 1\nheight: 1\nsampler: poisson\nthreshold: 5\npoisson_pool: 65536\n' "$S" >"$T/j.yaml"
refused "pool 65536 at t=5" "$T/j.yaml" "6:15: poisson_pool: 65536 sets of up to [0-9]* points (poisson t=5) is .* (limit 3.36e+07)"
printf 'scene: %s\nwidth: 300\nheight: 300\nlight_sampler: poisson\nlight_threshold: 0.0708\n' "$S" >"$T/j.yaml"
refused "fresh poisson light sets at 0.0708, 300x300" "$T/j.yaml" "5:18: light_threshold: 0.0708 draws a fresh poisson set .* per pixel and light"
printf 'scenes: [%s]\nwidth: 2\nreference: { sampler: jitter, threshold: 50 }\nvariants:\n  - { sampler: jitter }\n  - { sampler: poisson, threshold: 1, poisson_pool: 4096 }\n' "$S" >"$T/c.yaml"
refused "a compare variant's pool" "$T/c.yaml" "6:53: poisson_pool: 4096 sets"
# within the limits: a pool of 64 at t=5 renders
printf 'scene: %s\nwidth: 2\nheight: 2\nprocesses: 1\nsampler: poisson\nthreshold: 5\npoisson_pool: 64\n' "$S" >"$T/j.yaml"
"$WORKER" --quiet --out "$T/out" "$T/j.yaml" 2>"$T/err"; rc=$?
check "pool 64 at t=5 renders (rc $rc: $(cat "$T/err"))" [ "$rc" -eq 0 ]
finish
