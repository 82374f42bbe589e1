#!/bin/sh
# End to end, SPEC conformance as a user drives it: the command line's overrides, the job file's
# output names and formats, and YAML as written by hand.
. tests/lib.sh
root=$(pwd)

job() { # job FILE extra-yaml-lines...
    f=$1; shift
    { echo "scene: $root/scenes/checker.yaml"; echo "width: 8"; echo "height: 6"; echo "threshold: 50"
      echo "light_threshold: 50"; for l in "$@"; do echo "$l"; done; } >"$f"
}

# --processes N overrides the job even when an earlier run left current outputs: the image is
# the same, but the sidecar must describe the render that was asked for.
job "$T/p.yaml"
"$WORKER" --quiet --out "$T/o" "$T/p.yaml" 2>/dev/null
"$WORKER" --quiet --out "$T/o" --processes 3 "$T/p.yaml" 2>"$T/err"; rc=$?
check "--processes 3 after a default run exits 0 (got $rc)" [ "$rc" -eq 0 ]
check "--processes 3 after a default run: sidecar says 3" grep -q '"processes": 3' "$T/o/p/p.json"
check "--processes 3 after a default run: rendered, not skipped" sh -c "! grep -q 'up to date' '$T/err'"
"$WORKER" --quiet --out "$T/o" --processes 3 "$T/p.yaml" 2>"$T/err"
check "the same --processes again is up to date" grep -q 'up to date' "$T/err"
"$WORKER" --quiet --out "$T/o" "$T/p.yaml" 2>"$T/err"
check "back to the job's processes: rendered again" grep -q '"processes": 2' "$T/o/p/p.json"
"$WORKER" --quiet --out "$T/o" --processes 2 "$T/p.yaml" 2>"$T/err"
check "--processes equal to the job's is up to date" grep -q 'up to date' "$T/err"

# YAML merge keys: a job's own keys win over the merged ones
printf 'scene: %s/scenes/checker.yaml\nsampler: jitter\n<<: {width: 8, height: 6, threshold: 50, sampler: random}\n' "$root" >"$T/merge.yaml"
"$WORKER" --quiet --out "$T/o" "$T/merge.yaml" 2>"$T/err"; rc=$?
check "a job with a merge key renders (got $rc: $(head -n 1 "$T/err"))" [ "$rc" -eq 0 ]
check "merged threshold 50 and own sampler jitter" sh -c "grep -q '\"threshold\": 50' '$T/o/merge/merge.json' && grep -q '\"sampler\": \"jitter\"' '$T/o/merge/merge.json'"

# --opt=value as well as --opt value (GNU style; pbrt and Slurm take both); "--" ends the options
"$WORKER" --quiet --out="$T/eq" --processes=3 "$T/p.yaml" 2>"$T/err"; rc=$?
check "--out=DIR --processes=3 exit 0 (got $rc: $(head -n 1 "$T/err"))" [ "$rc" -eq 0 ]
check "--out=DIR writes under DIR" [ -s "$T/eq/p/p.png" ]
check "--processes=3 is taken" grep -q '"processes": 3' "$T/eq/p/p.json"
cp "$T/p.yaml" "$T/--p.yaml"
(cd "$T" && "$WORKER" --quiet --out "$T/dd" -- --p.yaml 2>"$T/err"); rc=$?
check "after --, --p.yaml is a job file (got $rc: $(head -n 1 "$T/err"))" [ "$rc" -eq 0 ]
check "after --, --p.yaml rendered" [ -s "$T/dd/--p/--p.png" ]
"$WORKER" diff "$T/o/p/p.png" "$T/eq/p/p.png" --max-rmse=0 >/dev/null 2>"$T/err"; rc=$?
check "diff --max-rmse=0 of identical images exits 0 (got $rc: $(head -n 1 "$T/err"))" [ "$rc" -eq 0 ]

# an empty --out or --queue is a usage error, not the file system's root (--out "" wrote
# /NAME/NAME.png; a regression is cleaned up below)
e=e2e-cli-empty-out-$$
cp "$T/p.yaml" "$T/$e.yaml"
for opt in --out --queue; do
    (cd "$T" && "$WORKER" --quiet "$opt" "" "$e.yaml" 2>"$T/err"); rc=$?
    check "$opt \"\" exits 2 (got $rc)" [ "$rc" -eq 2 ]
    check "$opt \"\" says why in one line" sh -c "[ \$(grep -c . '$T/err') -eq 1 ] && grep -q -- '$opt' '$T/err'"
done
check "nothing written at /$e" [ ! -e "/$e" ]
rm -rf "/${e:?}"

# bad input found only when rendering (here --out is a file) still names the job file, so a run of
# several jobs says which one it was
: >"$T/afile"
"$WORKER" --quiet --out "$T/afile" "$T/p.yaml" 2>"$T/err"; rc=$?
check "--out naming a file exits 2 (got $rc)" [ "$rc" -eq 2 ]
check "--out naming a file: the error names the job file ($(head -n 1 "$T/err"))" grep -q "^$T/p.yaml: cannot create directory" "$T/err"

# numbers on the command line are decimals, as in a job file (strtod took --processes 0x2)
"$WORKER" --quiet --out "$T/hex" --processes 0x2 "$T/p.yaml" 2>"$T/err"; rc=$?
check "--processes 0x2 exits 2 (got $rc)" [ "$rc" -eq 2 ]

# a lease under 0.1 s cannot be renewed in time (renewed every quarter of it): refused
mkdir -p "$T/q"
"$WORKER" --queue "$T/q" --once --lease-timeout 0.05 2>"$T/err"; rc=$?
check "--lease-timeout 0.05 exits 2 (got $rc)" [ "$rc" -eq 2 ]
check "--lease-timeout 0.05 says the range" grep -q 'lease-timeout must be a number of seconds in \[0.1,' "$T/err"

# the summary line counts processes in the singular too
"$WORKER" --quiet --out "$T/one" --processes 1 "$T/p.yaml" 2>"$T/err"
check "summary says '1 process,' ($(cat "$T/err"))" grep -q ', 1 process, ' "$T/err"

# --processes joins the outputs' match in a queue too: a job queued again and drained with another
# count renders again (its sidecar records the count), as on the command line
mkdir -p "$T/qp"
printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nthreshold: 50\n' "$(pwd)" >"$T/qp.yaml"
cp "$T/qp.yaml" "$T/qp/j.yaml"
"$WORKER" --quiet --queue "$T/qp" --once 2>/dev/null
cp "$T/qp.yaml" "$T/qp/j.yaml"
"$WORKER" --quiet --queue "$T/qp" --once --processes 1 2>"$T/err"
check "queue with --processes 1 renders again ($(cat "$T/err"))" grep -q '"processes": 1,' "$T/qp/done/j/j.json"

finish
