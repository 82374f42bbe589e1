#!/bin/sh
# e2e_queue_names: two queued job files of one `name:` would write the same DIR/done/<name>/; the
# second is filed in failed/ (exit 2) with a log naming the first, its outputs left alone. The
# same job file queued again after an edit renders again. A compare job's name counts the same.
. "$(dirname "$0")/lib.sh"
root=$(cd "$(dirname "$0")/.." && pwd)
job() { # job FILE SEED
    printf 'name: x\nscene: %s/scenes/checker.yaml\nwidth: 8\nthreshold: 50\nprocesses: 1\nseed: %s\n' "$root" "$2" >"$1"
}
Q=$T/q; mkdir -p "$Q"
job "$Q/a.yaml" 1; touch -d '1 minute ago' "$Q/a.yaml"
job "$Q/b.yaml" 2
"$WORKER" --queue "$Q" --once --quiet 2>"$T/log"; rc=$?
check "second file of one name: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "the first is done" [ -f "$Q/done/a.yaml" ]
check "the second is in failed/" [ -f "$Q/failed/b.yaml" ]
check "its log names the first: $(cat "$Q/failed/b.log" 2>/dev/null)" grep -q 'name: "x" is taken: .*done/x/ holds the outputs of .*a.yaml' "$Q/failed/b.log"
check "stderr says so, at the name key: $(head -n 1 "$T/log")" grep -q 'b.yaml:1:7: name: "x" is taken' "$T/log"
check "the first's outputs are its own (seed 1)" grep -q '"seed": 1,' "$Q/done/x/x.json"
# the same file queued again, edited: rendered again
job "$Q/a.yaml" 3
"$WORKER" --queue "$Q" --once --quiet 2>"$T/log2"; rc=$?
check "the same file re-queued after an edit: exit 0 (got $rc: $(cat "$T/log2"))" [ "$rc" -eq 0 ]
check "... rendered again (seed 3)" grep -q '"seed": 3,' "$Q/done/x/x.json"
# a compare job of that name
printf 'name: x\nscenes: [%s/scenes/checker.yaml]\nwidth: 8\nthreshold: 50\nvariants: [{ sampler: jitter }]\n' "$root" >"$Q/c.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/log3"; rc=$?
check "a compare job of a taken name: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "... filed in failed/ with a log naming the first" grep -q 'holds the outputs of .*a.yaml' "$Q/failed/c.log"
check "... wrote nothing into the folder" [ "$(ls "$Q/done/x" | sort | tr '\n' ' ')" = "x.json x.png " ]
# two compare jobs of their own names share DIR/done/.cache/ (the references): no conflict there
Q=$T/q2; mkdir -p "$Q"
for n in c1 c2; do
    t=1; [ "$n" = c2 ] && t=2
    printf 'scenes: [%s/scenes/checker.yaml]\nwidth: 8\nthreshold: 50\nreference: { sampler: jitter, threshold: %s }\nvariants: [{ sampler: jitter }]\n' \
        "$root" "$t" >"$Q/$n.yaml"
done
touch -d '1 minute ago' "$Q/c1.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/log4"; rc=$?
check "two compare jobs sharing the reference cache: exit 0 (got $rc: $(cat "$T/log4"))" [ "$rc" -eq 0 ]
check "... both done" sh -c "[ -f '$Q/done/c1.yaml' ] && [ -f '$Q/done/c2.yaml' ]"
# a job file named in Latin-1 and one with a tab in its name (their sidecars say \ufffd, \u0009):
# queued again, each is the same file, not another of its name
for f in "$(printf 'caf\351.yaml')" "$(printf 'a\tb.yaml')"; do
    Q=$T/q3; rm -rf "$Q"; mkdir -p "$Q"
    job "$Q/$f" 1
    "$WORKER" --queue "$Q" --once --quiet 2>"$T/log5"; rc=$?
    check "a job file named '$f': exit 0 (got $rc: $(cat "$T/log5"))" [ "$rc" -eq 0 ]
    job "$Q/$f" 4
    "$WORKER" --queue "$Q" --once --quiet 2>"$T/log6"; rc=$?
    check "... queued again after an edit: exit 0 (got $rc: $(cat "$T/log6"))" [ "$rc" -eq 0 ]
    check "... rendered again (seed 4)" grep -q '"seed": 4,' "$Q/done/x/x.json"
done

# a job file whose stem is over 127 bytes (and has no name:) goes to failed/ saying why, never cut
Q=$T/ql; mkdir -p "$Q"
long=$(printf 'é%.0s' $(seq 1 100))
printf 'scene: %s/scenes/checker.yaml\nwidth: 8\nthreshold: 50\nprocesses: 1\n' "$root" >"$Q/$long.yaml"
"$WORKER" --queue "$Q" --once --quiet 2>"$T/loglong"; rc=$?
check "a 200-byte stem in a queue: exit 2 (got $rc)" [ "$rc" -eq 2 ]
check "a 200-byte stem in a queue: filed in failed/" [ -f "$Q/failed/$long.yaml" ]
check "a 200-byte stem in a queue: its log says why" grep -q 'give the job a name:' "$Q/failed/$long.log"
check "a 200-byte stem in a queue: nothing in done/" [ -z "$(ls "$Q/done")" ]
finish
