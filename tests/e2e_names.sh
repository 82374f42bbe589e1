#!/bin/sh
# e2e_names: job files of one name on one command line would share OUT/<name>/: the later one is
# refused (exit 2), compare jobs included, and the earlier one's outputs stay as they were.
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/.." && pwd)

compare_job() { # compare_job FILE SAMPLER: a one-image compare job named cmp
    printf 'name: cmp\nscenes: [%s/scenes/checker.yaml]\nwidth: 8\nheight: 8\nreference: { sampler: jitter, threshold: 20 }\nvariants:\n  - { sampler: %s, threshold: 50 }\n' \
        "$root" "$2" >"$1"
}
mkdir -p "$T/a" "$T/b"
compare_job "$T/a/c.yaml" jitter
compare_job "$T/b/c.yaml" random
printf 'name: cmp\nscene: %s/scenes/checker.yaml\nwidth: 8\nheight: 8\nthreshold: 50\n' "$root" >"$T/plain.yaml"

# 1. two compare jobs of one name: the second would replace the first's summary and report
"$WORKER" --quiet --out "$T/o1" "$T/a/c.yaml" "$T/b/c.yaml" 2>"$T/e1"; rc=$?
check "two compare jobs of one name: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "two compare jobs of one name: one line names both files" \
    grep -q "^$T/b/c.yaml: name \"cmp\" is also the name of $T/a/c.yaml" "$T/e1"
check "two compare jobs of one name: the first's summary kept" grep -q '^checker,jitter-t50,' "$T/o1/cmp/summary.csv"
check "two compare jobs of one name: the second rendered nothing" [ ! -e "$T/o1/cmp/checker-random-t50-t50-s1.png" ]

# 2. a plain job and a compare job of one name, either way round
"$WORKER" --quiet --out "$T/o2" "$T/plain.yaml" "$T/a/c.yaml" 2>"$T/e2"; rc=$?
check "plain then compare of one name: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "plain then compare of one name: no compare outputs" [ ! -e "$T/o2/cmp/summary.csv" ]
"$WORKER" --quiet --out "$T/o3" "$T/a/c.yaml" "$T/plain.yaml" 2>"$T/e3"; rc=$?
check "compare then plain of one name: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "compare then plain of one name: no plain image" [ ! -e "$T/o3/cmp/cmp.png" ]

# 3. the same compare file twice is one job (the second time current)
"$WORKER" --quiet --out "$T/o4" "$T/a/c.yaml" "$T/a/c.yaml" 2>"$T/e4"; rc=$?
check "the same compare file twice: exit 0 (got $rc)" [ "$rc" -eq 0 ]


# 4. a stem over 127 bytes names no job: refused (exit 2, one line naming the file), never cut (a
#    cut split a UTF-8 character, and two files differing after byte 127 shared one folder)
long=$(printf 'é%.0s' $(seq 1 100))
printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nthreshold: 50\n' "$root" >"$T/$long.yaml"
"$WORKER" --quiet --out "$T/o5" "$T/$long.yaml" 2>"$T/e5"; rc=$?
check "a 200-byte stem: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "a 200-byte stem: one line naming the file and asking for name:" \
    sh -c "[ \$(wc -l <'$T/e5') -eq 1 ] && grep -q '^$T/$long.yaml:1:1: name: .*give the job a name:' '$T/e5'"
check "a 200-byte stem: nothing written" [ ! -e "$T/o5" ]
printf 'name: longok\nscene: %s/scenes/checker.yaml\nwidth: 8\nthreshold: 50\n' "$root" >"$T/$long.yaml"
"$WORKER" --quiet --out "$T/o5" "$T/$long.yaml" 2>/dev/null; rc=$?
check "a 200-byte stem with name: renders (got $rc)" sh -c "[ $rc -eq 0 ] && [ -f '$T/o5/longok/longok.png' ]"
s127=$(printf 'a%.0s' $(seq 1 127))
printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nthreshold: 50\n' "$root" >"$T/$s127.yaml"
"$WORKER" --quiet --out "$T/o6" "$T/$s127.yaml" 2>/dev/null; rc=$?
check "a 127-byte stem names its job (got $rc)" sh -c "[ $rc -eq 0 ] && [ -d '$T/o6/$s127' ]"
printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nthreshold: 50\n' "$root" >"$T/${s127}b.yaml"
"$WORKER" --quiet --out "$T/o6" "$T/${s127}b.yaml" 2>/dev/null; rc=$?
check "a 128-byte stem is refused, not written over the 127-byte one's folder (got $rc)" [ "$rc" -eq 2 ]
# a compare job named for its stem, and a scene whose stem names its outputs: the same rule
printf 'scenes: [%s/scenes/checker.yaml]\nwidth: 8\nreference: { sampler: jitter, threshold: 20 }\nvariants:\n  - { sampler: jitter, threshold: 50 }\n' "$root" >"$T/c$long.yaml"
"$WORKER" --quiet --out "$T/o7" "$T/c$long.yaml" 2>"$T/e7"; rc=$?
check "a compare job's 201-byte stem: exit 2 (got $rc)" sh -c "[ $rc -eq 2 ] && grep -q 'give the job a name:' '$T/e7'"
cp "$root/scenes/checker.yaml" "$T/$long-scene.yaml"
printf 'name: cs\nscenes: ["%s"]\nwidth: 8\nreference: { sampler: jitter, threshold: 20 }\nvariants:\n  - { sampler: jitter, threshold: 50 }\n' "$T/$long-scene.yaml" >"$T/cs.yaml"
"$WORKER" --quiet --out "$T/o8" "$T/cs.yaml" 2>"$T/e8"; rc=$?
check "a scene's 206-byte stem: exit 2 (got $rc)" sh -c "[ $rc -eq 2 ] && grep -q 'rename the file' '$T/e8'"

finish
