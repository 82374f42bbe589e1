#!/bin/sh
# e2e_once: each input read once, each output renamed once (issue 29), counted with strace over
# the worker and its render processes: the job file is opened once per job (from the command
# line, and in a queue once after the claim), the scene file once (its one read is hashed and
# parsed), a reference image once (hashed and scored), for a compare job and a suite also each
# image texture and cached reference once, and every output (images, sidecar) is the target of
# exactly one rename, from a temporary name, with no temporary renamed into another temporary
# (no second staging).
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/.." && pwd)
if ! command -v strace >/dev/null 2>&1 || ! strace -f -o /dev/null true 2>/dev/null; then
    skip "strace is missing or cannot trace here"
    finish
    exit $?
fi
# under ASan (make asan) LeakSanitizer cannot run beneath ptrace: leaks are the untraced runs' to find
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
cp "$root/scenes/checker.yaml" "$T/scene.yaml"
opens() { grep "open[a-z]*([^\"]*\"$2\"" "$1" | grep -vc ' = -1 '; } # opens of path $2 (that open it)
renamed_to() { grep -E "rename[a-z0-9]*\(.*\"$2\"\) = 0" "$1" | grep -c .; } # renames onto path $2
renames() { grep -E 'rename[a-z0-9]*\(.*\) = 0' "$1"; }
traced() { # traced NAME WORKER-ARGS...: run the worker under strace into $T/NAME.log; check exit 0
    run=$1; shift
    strace -f -qq -e trace=open,openat,rename,renameat,renameat2 -o "$T/$run.log" "$WORKER" --quiet "$@" \
        2>"$T/$run.err"
    rc=$?
    check "$run: exit 0 (got $rc: $(tail -n 1 "$T/$run.err"))" [ "$rc" -eq 0 ]
}
once() { # once NAME WHAT PATH: PATH opened once in NAME's run
    got=$(opens "$T/$1.log" "$3")
    check "$1: $2 opened once (got $got)" [ "$got" -eq 1 ]
}
at_most_once() { # at_most_once NAME WHAT PATH: PATH opened at most once (a file this run wrote itself
    got=$(opens "$T/$1.log" "$3") # is kept in memory, never read back)
    check "$1: $2 opened at most once (got $got)" [ "$got" -le 1 ]
}
renamed_once() { # renamed_once NAME DIR FILE...: each FILE in DIR renamed into place once
    run=$1 into=$2; shift 2 # (check's own variables are d and its arguments)
    for f in "$@"; do
        got=$(renamed_to "$T/$run.log" "$into/$f")
        check "$run: $f renamed into place once (got $got)" [ "$got" -eq 1 ]
    done
    check "$run: no temporary renamed into another" sh -c "! grep -E 'rename[a-z0-9]*\\(.*\\.tmp\\..*\\.tmp\\.' '$T/$run.log'"
}
job() { # job FILE EXTRA-LINE: a tiny job on the copied scene
    printf 'scene: %s\nwidth: 16\nheight: 16\nthreshold: 50\nlight_threshold: 50\n%s\n' "$T/scene.yaml" "$2" >"$1"
}

# 1. one plain job from the command line, two images (output: [a list]) and a sidecar
job "$T/one.yaml" "output: [pic.png, pic.exr]"
traced one --out "$T/out" "$T/one.yaml"
once one "its job file" "$T/one.yaml"
once one "its scene file (for hash and parse alike)" "$T/scene.yaml"
renamed_once one "$T/out/one" pic.png pic.exr pic.json
three_renames() { # three renames in one.log, each from a temporary name
    [ "$(renames "$T/one.log" | grep -c .)" -eq 3 ] &&
        [ "$(renames "$T/one.log" | grep -c '\.tmp\.[A-Za-z0-9]*", ')" -eq 3 ]
}
check "one: three renames in all, each from a temporary: $(renames "$T/one.log" | tr '\n' ' ')" three_renames
check "one: both images written" eval '[ -s "$T/out/one/pic.png" ] && [ -s "$T/out/one/pic.exr" ]'

# 2. run again: current, nothing renamed; the job file and scene still read once (for the hash)
traced again --out "$T/out" "$T/one.yaml"
check "again: up to date, nothing renamed" [ "$(renames "$T/again.log" | grep -c .)" -eq 0 ]
once again "the job file" "$T/one.yaml"
once again "the scene file" "$T/scene.yaml"

# 2b. a job scored against a reference image: the reference opened once (its bytes hashed and
#     decoded), the error figures in the sidecar
cp "$T/out/one/pic.exr" "$T/ref.exr"
job "$T/scored.yaml" "reference: $T/ref.exr"
traced scored --out "$T/out" "$T/scored.yaml"
once scored "its reference image" "$T/ref.exr"
check "scored: the error against the reference in the sidecar" grep -q '"relmse"' "$T/out/scored/scored.json"

# 3. a queue: the claimed file is opened once after the claim (the scan reads the waiting file for
#    its priority before), the scene once, each output renamed once
Q=$T/q; mkdir -p "$Q"
job "$Q/qj.yaml" "processes: 1"
traced queue --queue "$Q" --once
once queue "the claimed file" "$Q/running/qj.yaml"
once queue "the scene file" "$T/scene.yaml"
renamed_once queue "$Q/done/qj" qj.png qj.json

# 4. a compare job: its file opened once, its outputs renamed once each
printf 'scenes: [%s]\nwidth: 8\nheight: 8\nthreshold: 50\nlight_threshold: 50\nreference: { threshold: 50, light_threshold: 50 }\nvariants:\n  - { sampler: jitter }\n' \
    "$T/scene.yaml" >"$T/cmp.yaml"
traced cmp --out "$T/out" "$T/cmp.yaml"
once cmp "its job file" "$T/cmp.yaml"
renamed_once cmp "$T/out/cmp" scene-jitter-t50-s1.png scene-jitter-t50-s1.exr scene-jitter-t50-s1.json summary.csv

# 5. a batch task's share of a study (--part I/N): its job file opened once
traced share --out "$T/share" --part 0/1 "$T/cmp.yaml"
once share "its job file" "$T/cmp.yaml"

# 6. a compare job in a queue, spread: the claimed file opened once (its bytes, as read, become
#    the study's study.job), then study.job once per entry: the reference's two halves, the image, the gather
Q2=$T/q2; mkdir -p "$Q2"
cp "$T/cmp.yaml" "$Q2/cq.yaml"
traced spread --queue "$Q2" --once
once spread "the claimed compare job" "$Q2/running/cq.yaml"
got=$(opens "$T/spread.log" "$Q2/spread/cq/study.job")
check "spread: study.job opened once per entry, 4 entries (got $got)" [ "$got" -eq 4 ]
renamed_once spread "$Q2/done/cq" scene-jitter-t50-s1.png summary.csv verdict.json

# 7. a compare job of two variants and two seeds on a scene with an image texture: the scene file
#    opened once for the whole study (parsed at load, its parse and hash used by every render), the
#    texture once (its bytes hashed and decoded), each half of the reference read back at most
#    once after its render, every output renamed into place once
mkdir -p "$T/tex"
cp "$root/scenes/textures/planet.png" "$T/tex/planet.png"
sed -e 's/board: { type: checker.*/board: { type: image, file: tex\/planet.png }/' "$T/scene.yaml" >"$T/texd.yaml"
study() { # study FILE NAME SCENE: a compare job of two variants and two seeds
    printf 'name: %s\nscenes: [%s]\nwidth: 8\nheight: 8\nthreshold: 50\nlight_threshold: 50\nseeds: [1, 2]\n' "$2" "$3" >"$1"
    printf 'reference: { threshold: 50, light_threshold: 50 }\nvariants:\n  - { sampler: jitter }\n  - { sampler: random }\n' >>"$1"
}
study "$T/tx.yaml" tx "$T/texd.yaml"
traced tx --out "$T/tout" "$T/tx.yaml"
once tx "its job file" "$T/tx.yaml"
once tx "its scene file, for 4 images and 2 reference halves" "$T/texd.yaml"
once tx "its image texture" "$T/tex/planet.png"
for f in "$T"/tout/.cache/ref-texd-*.exr; do at_most_once tx "the reference $(basename "$f")" "$f"; done
check "tx: a reference and its two halves cached" [ "$(ls "$T"/tout/.cache/ref-texd-*.exr | grep -c .)" -eq 3 ]
renamed_once tx "$T/tout/tx" texd-jitter-t50-s1.png texd-jitter-t50-s2.exr texd-random-t50-s2.png \
    texd-random-t50-s1.json summary.csv chart.svg report.html verdict.json

# 8. the same study run again (everything current): the scene, texture and cached references
#    still opened once each, nothing renamed
traced tx2 --out "$T/tout" "$T/tx.yaml"
once tx2 "its scene file" "$T/texd.yaml"
once tx2 "its image texture" "$T/tex/planet.png"
for f in "$T"/tout/.cache/ref-texd-*.exr; do once tx2 "the cached reference $(basename "$f")" "$f"; done

# 9. a suite of two studies sharing the scene (and its reference's settings): the scene and the
#    texture opened once for the whole suite, the reference rendered once and read back at most
#    once (the second study takes it from the first)
study "$T/sa.yaml" sa "$T/texd.yaml"
study "$T/sb.yaml" sb "$T/texd.yaml"
printf 'name: suite\nstudies: [sa.yaml, sb.yaml]\n' >"$T/suite.yaml"
traced suite --out "$T/sout" "$T/suite.yaml"
once suite "its job file" "$T/suite.yaml"
once suite "the first study's file" "$T/sa.yaml"
once suite "the scene both studies render" "$T/texd.yaml"
once suite "the image texture" "$T/tex/planet.png"
for f in "$T"/sout/suite/.cache/ref-texd-*.exr; do at_most_once suite "the shared reference $(basename "$f")" "$f"; done
check "suite: one reference (and its halves) for both studies" \
    [ "$(ls "$T"/sout/suite/.cache/ref-texd-*.exr | grep -c .)" -eq 3 ]
renamed_once suite "$T/sout/suite" sa/texd-jitter-t50-s1.png sb/texd-random-t50-s2.exr summary.csv \
    report.html verdict.json
finish
