#!/bin/sh
# e2e_once: each input read once, each output renamed once (issue 29), counted with strace over
# the worker and its render processes: the job file is opened once per job (from the command
# line, and in a queue once after the claim), the scene file once (its one read is hashed and
# parsed), and every output (images, sidecar) is the target of exactly one rename, from a
# temporary name, with no temporary renamed into another temporary (no second staging).
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/.." && pwd)
if ! command -v strace >/dev/null 2>&1 || ! strace -f -o /dev/null true 2>/dev/null; then
    skip "strace is missing or cannot trace here"
    finish
    exit $?
fi
cp "$root/scenes/checker.yaml" "$T/scene.yaml"
opens() { grep -c "open[a-z]*([^\"]*\"$2\"" "$1"; }                      # opens of path $2
renamed_to() { grep -E "rename[a-z0-9]*\(.*\"$2\"\) = 0" "$1" | grep -c .; } # renames onto path $2
renames() { grep -E 'rename[a-z0-9]*\(.*\) = 0' "$1"; }

# 1. one plain job from the command line, two images (output: [a list]) and a sidecar
printf 'scene: %s\nwidth: 16\nheight: 16\nthreshold: 50\nlight_threshold: 50\nprocesses: 2\noutput: [pic.png, pic.exr]\n' \
    "$T/scene.yaml" >"$T/one.yaml"
strace -f -qq -e trace=open,openat,rename,renameat,renameat2 -o "$T/one.log" \
    "$WORKER" --quiet --out "$T/out" "$T/one.yaml" 2>"$T/one.err"; rc=$?
check "one job: exit 0 (got $rc: $(cat "$T/one.err"))" [ "$rc" -eq 0 ]
check "one job: its job file opened once (got $(opens "$T/one.log" "$T/one.yaml"))" \
    [ "$(opens "$T/one.log" "$T/one.yaml")" -eq 1 ]
check "one job: its scene file opened once, for hash and parse alike (got $(opens "$T/one.log" "$T/scene.yaml"))" \
    [ "$(opens "$T/one.log" "$T/scene.yaml")" -eq 1 ]
for f in pic.png pic.exr pic.json; do
    n=$(renamed_to "$T/one.log" "$T/out/one/$f")
    check "one job: $f renamed into place once (got $n)" [ "$n" -eq 1 ]
done
check "one job: three renames in all, each from a temporary: $(renames "$T/one.log" | tr '\n' ' ')" \
    [ "$(renames "$T/one.log" | grep -c .)" -eq 3 ] && [ "$(renames "$T/one.log" | grep -c '\.tmp\.[A-Za-z0-9]*", ')" -eq 3 ]
check "one job: no temporary renamed into another" sh -c "! grep -E 'rename[a-z0-9]*\\(.*\\.tmp\\..*\\.tmp\\.' '$T/one.log'"
check "one job: both images written" [ -s "$T/out/one/pic.png" ] && [ -s "$T/out/one/pic.exr" ]

# 2. run again: current, nothing renamed; the job file and scene still read once (for the hash)
strace -f -qq -e trace=open,openat,rename,renameat,renameat2 -o "$T/again.log" \
    "$WORKER" --quiet --out "$T/out" "$T/one.yaml" 2>"$T/again.err"
check "again: up to date, nothing renamed" [ "$(renames "$T/again.log" | grep -c .)" -eq 0 ]
check "again: job file and scene opened once each" \
    [ "$(opens "$T/again.log" "$T/one.yaml")" -eq 1 ] && [ "$(opens "$T/again.log" "$T/scene.yaml")" -eq 1 ]

# 3. a queue: the claimed file is opened once after the claim (the scan reads the waiting file for
#    its priority before), the scene once, each output renamed once
Q=$T/q; mkdir -p "$Q"
printf 'scene: %s\nwidth: 16\nheight: 16\nthreshold: 50\nlight_threshold: 50\nprocesses: 1\n' "$T/scene.yaml" >"$Q/qj.yaml"
strace -f -qq -e trace=open,openat,rename,renameat,renameat2 -o "$T/q.log" \
    "$WORKER" --queue "$Q" --once --quiet 2>"$T/q.err"; rc=$?
check "queue: exit 0 (got $rc: $(cat "$T/q.err"))" [ "$rc" -eq 0 ]
check "queue: the claimed file opened once (got $(opens "$T/q.log" "$Q/running/qj.yaml"))" \
    [ "$(opens "$T/q.log" "$Q/running/qj.yaml")" -eq 1 ]
check "queue: the scene opened once (got $(opens "$T/q.log" "$T/scene.yaml"))" \
    [ "$(opens "$T/q.log" "$T/scene.yaml")" -eq 1 ]
for f in qj.png qj.json; do
    n=$(renamed_to "$T/q.log" "$Q/done/qj/$f")
    check "queue: $f renamed into place once (got $n)" [ "$n" -eq 1 ]
done

# 4. a compare job: its file opened once
printf 'scenes: [%s]\nwidth: 8\nheight: 8\nthreshold: 50\nlight_threshold: 50\nreference: { threshold: 50, light_threshold: 50 }\nvariants:\n  - { sampler: jitter }\n' \
    "$T/scene.yaml" >"$T/cmp.yaml"
strace -f -qq -e trace=open,openat,rename,renameat,renameat2 -o "$T/cmp.log" \
    "$WORKER" --quiet --out "$T/out" "$T/cmp.yaml" 2>"$T/cmp.err"; rc=$?
check "compare: exit 0 (got $rc: $(tail -n 1 "$T/cmp.err"))" [ "$rc" -eq 0 ]
check "compare: its job file opened once (got $(opens "$T/cmp.log" "$T/cmp.yaml"))" \
    [ "$(opens "$T/cmp.log" "$T/cmp.yaml")" -eq 1 ]
check "compare: no temporary renamed into another" sh -c "! grep -E 'rename[a-z0-9]*\\(.*\\.tmp\\..*\\.tmp\\.' '$T/cmp.log'"
finish
