#!/bin/sh
# End to end: a job file nested 200k brackets deep (far under the 8 MiB size limit) is refused
# while libyaml parses it, in well under a second, with file:line:col; composing it first took
# time quadratic in the depth (past 20 s here). A queue holding it files it in failed/ and keeps
# draining the others. Also many anchors and aliases, which libyaml's composer looks up one by one.
. tests/lib.sh
root=$(pwd)

deep() { # deep FILE N: width nested N flow lists deep
    awk -v n="$2" -v s="$root/scenes/checker.yaml" 'BEGIN {
        printf "scene: %s\nwidth: ", s; for (i = 0; i < n; i++) printf "["; printf "1";
        for (i = 0; i < n; i++) printf "]"; printf "\n" }' >"$1"
}
tiny() {
    { echo "scene: $root/scenes/checker.yaml"; echo "width: 16"; echo "height: 16"; echo "threshold: 50"
      echo "light_threshold: 50"; echo "processes: 1"; } >"$1"
}

deep "$T/deep.yaml" 200000
check "deep: the file is under 8 MiB" [ "$(wc -c <"$T/deep.yaml")" -lt 8388608 ]
# bounded generously (5 s) for a loaded machine: the refusal takes milliseconds
timeout 5 "$WORKER" --quiet --out "$T/out" "$T/deep.yaml" 2>"$T/deep.err"; rc=$?
check "deep: refused with exit 2 within 5 s (got $rc)" [ "$rc" -eq 2 ]
check "deep: one line at file:line:col" grep -qE "^$T/deep.yaml:2:[0-9]+: nesting deeper than 32 levels" "$T/deep.err"
check "deep: nothing written" [ ! -e "$T/out/deep" ]

# the flow mapping form too, and block nesting
awk 'BEGIN { printf "a: "; for (i = 0; i < 200000; i++) printf "{a: "; printf "1";
    for (i = 0; i < 200000; i++) printf "}"; printf "\n" }' >"$T/deepmap.yaml"
timeout 5 "$WORKER" --quiet --out "$T/out" "$T/deepmap.yaml" 2>"$T/deepmap.err"; rc=$?
check "deep map: refused with exit 2 within 5 s (got $rc)" [ "$rc" -eq 2 ]
check "deep map: at file:line:col" grep -qE "^$T/deepmap.yaml:1:[0-9]+: nesting deeper than 32" "$T/deepmap.err"

# 200k anchors, then 200k aliases to the last: the composer looks every one up in a list
awk 'BEGIN { printf "x: ["; for (i = 0; i < 200000; i++) printf "&a%d 1, ", i;
    for (i = 0; i < 200000; i++) printf "*a199999, "; printf "1]\n" }' >"$T/anchors.yaml"
timeout 5 "$WORKER" --quiet --out "$T/out" "$T/anchors.yaml" 2>"$T/anchors.err"; rc=$?
check "anchors: refused with exit 2 within 5 s (got $rc)" [ "$rc" -eq 2 ]
check "anchors: at file:line:col" grep -qE "^$T/anchors.yaml:1:[0-9]+: .*anchors" "$T/anchors.err"

# a queue holding the deep file keeps draining the others
Q=$T/q; mkdir -p "$Q"
for i in 1 2 3 4 5; do tiny "$Q/j$i.yaml"; done
deep "$Q/deep.yaml" 200000
printf 'priority: 5\n' | cat - "$Q/deep.yaml" >"$Q/deep2.yaml" # read by the scan for its priority
timeout 60 "$WORKER" --queue "$Q" --once --quiet 2>"$T/q.log"; rc=$?
check "queue: the worker ends (exit 2: invalid jobs; got $rc)" [ "$rc" -eq 2 ]
check "queue: the 5 others are done" [ "$(ls "$Q"/done/j*.yaml 2>/dev/null | wc -l)" -eq 5 ]
check "queue: both deep files in failed/" eval '[ -f "$Q/failed/deep.yaml" ] && [ -f "$Q/failed/deep2.yaml" ]'
check "queue: its log gives file:line:col" grep -qE "deep.yaml:2:[0-9]+: nesting deeper" "$Q/failed/deep.log"
finish
