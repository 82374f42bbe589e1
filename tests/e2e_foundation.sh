#!/bin/sh
# End to end: a job renders to PNG + sidecar; any process split gives the same bytes;
# bad jobs exit 2 with file:line:col and write nothing; a killed child fails the job.
. tests/lib.sh
root=$(pwd)

job() { # job FILE extra-yaml-lines...
    f=$1; shift
    { echo "scene: $root/scenes/checker.yaml"; for l in "$@"; do echo "$l"; done; } >"$f"
}

# 1. a small render and its sidecar
job "$T/small.yaml" "width: 48" "height: 32" "threshold: 25" "light_threshold: 20"
"$WORKER" --quiet --out "$T/out" "$T/small.yaml" 2>"$T/err"; rc=$?
check "small render exits 0" [ "$rc" -eq 0 ]
check "image written" [ -s "$T/out/small/small.png" ]
check "sidecar written" [ -s "$T/out/small/small.json" ]
check "png signature" sh -c "head -c 8 '$T/out/small/small.png' | od -An -tx1 | tr -d ' \n' | grep -q 89504e470d0a1a0a"
for key in '"job": "small"' '"sampler": "random"' '"per_pixel_mean": 16' '"total"' '"wall_s"' '"cpu_s"' '"nonfinite_samples"' '"processes": 2' '"light_sample_sets"'; do
    check "sidecar has $key" grep -q "$key" "$T/out/small/small.json"
done
check "summary line names the job" grep -q "small: 48x32" "$T/err"
check "no temporary files left" sh -c "! ls -a '$T/out/small' | grep -q tmp"

# 2. byte-identical across process counts: checker (four paths at a time in double lanes) and the
# book's Cornell box (one BVH node: four paths at a time through the lanes);
# a pixel must depend only on seed and pixel
printf 'name: box\nscene: %s/scenes/cornell-book3.yaml\nwidth: 24\nheight: 24\nthreshold: 25\n' "$root" >"$T/box.yaml"
for job in small box; do
    for n in 1 2 3 8; do
        "$WORKER" --quiet --processes $n --out "$T/p$n" "$T/$job.yaml" 2>/dev/null
    done
    for n in 2 3 8; do
        check "$job: processes $n == processes 1" cmp -s "$T/p1/$job/$job.png" "$T/p$n/$job/$job.png"
    done
done
check "sidecar records processes 8" grep -q '"processes": 8' "$T/p8/small/small.json"
# a different seed changes the image
job "$T/seed2.yaml" "name: small" "width: 48" "height: 32" "threshold: 25" "light_threshold: 20" "seed: 2"
"$WORKER" --quiet --out "$T/s2" "$T/seed2.yaml" 2>/dev/null
check "seed 2 differs from seed 1" sh -c "! cmp -s '$T/p1/small/small.png' '$T/s2/small/small.png'"

# format from the output's extension (any case), png without one; format: names the default output
for spec in "x.ppm:x.ppm:P6" "x.PPM:x.PPM:P6" "x.Png:x.Png:PNG" "x:x:PNG"; do
    out=${spec%%:*}; rest=${spec#*:}; file=${rest%%:*}; magic=${rest#*:}
    job "$T/fmt.yaml" "width: 8" "threshold: 50" "output: $out"
    rm -rf "$T/fmt"; "$WORKER" --quiet --out "$T/fmt" "$T/fmt.yaml" 2>/dev/null
    check "output: $out is written as $magic" sh -c "head -c 4 '$T/fmt/fmt/$file' | grep -q '$magic'"
done
job "$T/fmt.yaml" "width: 8" "threshold: 50" "format: ppm"
rm -rf "$T/fmt"; "$WORKER" --quiet --out "$T/fmt" "$T/fmt.yaml" 2>/dev/null
check "format: ppm names the image fmt.ppm" sh -c "head -c 2 '$T/fmt/fmt/fmt.ppm' | grep -q P6"

# 3. bad jobs: exit 2, file:line:col, nothing under --out
bad() { # bad NAME EXPECTED-REGEX  (file already written to $T/NAME.yaml)
    rm -rf "$T/badout"
    "$WORKER" --quiet --out "$T/badout" "$T/$1.yaml" 2>"$T/$1.err"; rc=$?
    check "$1: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "$1: message matches '$2'" grep -Eq "$2" "$T/$1.err"
    check "$1: nothing written" [ ! -e "$T/badout" ]
}
job "$T/unknown.yaml" "width: 10" "treshold: 5"
bad unknown "unknown.yaml:3:1: treshold: unknown key.*did you mean \"threshold\""
job "$T/abc.yaml" "width: 10" "threshold: abc"
bad abc 'abc.yaml:3:12: threshold: must be a number in \(0, 100\], got "abc"'
printf 'scene: nowhere/missing.yaml\nwidth: 10\n' >"$T/missing.yaml"
bad missing 'missing.yaml:1:8: scene: no scene file'
printf 'scene: checker\nwidth: [10\n' >"$T/syntax.yaml"
bad syntax 'syntax.yaml:[0-9]+:[0-9]+: YAML syntax error'
job "$T/zero.yaml" "threshold: 0"
bad zero 'zero.yaml:2:12: threshold: must be a number in \(0, 100\]'
job "$T/sampler.yaml" "sampler: halton"
bad sampler 'sampler.yaml:2:10: sampler: unknown sampler "halton"'
job "$T/type.yaml" "width: wide"
bad type 'type.yaml:2:8: width: must be a whole number'
: >"$T/empty.yaml"
bad empty 'empty.yaml:1:1: empty file'
printf 'scene: %s\nwidth: 10\nwidth: 12\n' "$root/scenes/checker.yaml" >"$T/dup.yaml"
bad dup 'dup.yaml:3:1: width: duplicate key'
"$WORKER" --bogus 2>"$T/usage.err"; rc=$?
check "unknown option exits 2" [ "$rc" -eq 2 ]
check "unknown option: one line on stderr" [ "$(wc -l <"$T/usage.err")" -eq 1 ]
check "unknown option: the line names it" grep -q "^worker: unknown option --bogus" "$T/usage.err"
"$WORKER" 2>"$T/nojob.err"; rc=$?
check "no job file: exit 2, one line on stderr" sh -c "[ $rc -eq 2 ] && [ \$(wc -l <'$T/nojob.err') -eq 1 ]"
"$WORKER" diff "$T/a.png" 2>"$T/diff1.err"; rc=$?
check "diff with one image: exit 2, one line on stderr" sh -c "[ $rc -eq 2 ] && [ \$(wc -l <'$T/diff1.err') -eq 1 ]"
"$WORKER" --out 2>"$T/noval.err"; rc=$?
check "option without its value: exit 2, one line on stderr" sh -c "[ $rc -eq 2 ] && [ \$(wc -l <'$T/noval.err') -eq 1 ]"
# an argument holding a newline is escaped: still one line
"$WORKER" "$(printf -- '--x\ny')" 2>"$T/nl.err"; rc=$?
check "unknown option with a newline: exit 2, one line on stderr" sh -c "[ $rc -eq 2 ] && [ \$(wc -l <'$T/nl.err') -eq 1 ]"
"$WORKER" points poisson "$(printf '1\nx')" 2>"$T/nl2.err"; rc=$?
check "points threshold with a newline: exit 2, one line on stderr" sh -c "[ $rc -eq 2 ] && [ \$(wc -l <'$T/nl2.err') -eq 1 ]"
"$WORKER" --help >"$T/help.out"; rc=$?
check "--help exits 0 and shows usage" sh -c "[ $rc -eq 0 ] && grep -q 'usage: worker JOB.yaml' '$T/help.out'"
check "--version" sh -c "'$WORKER' --version | grep -Eq '^worker [0-9]'"

# 4. a render child killed mid-render: exit 1, a message naming the signal, no image
job "$T/slow.yaml" "width: 200" "height: 200" "threshold: 3" "light_threshold: 5"
"$WORKER" --quiet --out "$T/killed" "$T/slow.yaml" 2>"$T/killed.err" &
wpid=$!
child=$(render_child "$wpid")
sleep 0.3
[ -n "$child" ] && kill -9 "$child"
wait "$wpid"; rc=$?
check "killed child: found a child to kill" [ -n "$child" ]
check "killed child: exit 1 (got $rc)" [ "$rc" -eq 1 ]
check "killed child: message names signal 9" grep -q "killed by signal 9" "$T/killed.err"
check "killed child: no image" [ ! -e "$T/killed/slow/slow.png" ]
check "killed child: no sidecar" [ ! -e "$T/killed/slow/slow.json" ]
check "killed child: no empty output folder left" [ ! -e "$T/killed/slow" ]
# 5. SIGTERM to a plain render: no image, no sidecar, not even an empty folder
"$WORKER" --quiet --out "$T/term" "$T/slow.yaml" 2>/dev/null &
wpid=$!
render_child "$wpid" >/dev/null
sleep 0.3
kill -TERM "$wpid"
wait "$wpid"; rc=$?
check "SIGTERM: the worker stops (exit $rc)" [ "$rc" -ne 0 ]
check "SIGTERM: nothing under --out" [ ! -e "$T/term/slow" ]
# 6. a failed render removes no folder it did not make: another render of a job of the same name
#    (or a user) may have made OUT/<name>/ meanwhile, and be about to write into it
"$WORKER" --quiet --out "$T/own" "$T/slow.yaml" 2>/dev/null &
wpid=$!
child=$(render_child "$wpid")
mkdir -p "$T/own/slow"
[ -n "$child" ] && kill -9 "$child"
wait "$wpid"; rc=$?
check "killed child, folder made meanwhile: exit 1 (got $rc)" [ "$rc" -eq 1 ]
check "killed child: the folder another process made meanwhile is left alone" [ -d "$T/own/slow" ]
finish
